#pragma once
// The objects on a plate: the pieces of the model's footprint over all
// layers. A slicer's copies, or different models, stand apart; one model's
// parts that touch on any layer are one object. METHOD reports unheld area
// per model, and exact copies are recognised object by object.
#include <functional>
#include <vector>

#include "layers/layer_stack.hpp"
#include "layers/raster.hpp"

namespace scaffold::layers {

// Beads closer than about this belong to one object.
inline constexpr double kObjectJoin = 1.0;

// A bead of an object: not a skirt or brim, a wipe tower or a purge line.
bool model_bead(const Layer& layer, const Segment& s);

class ObjectMap {
public:
    // Every model bead of every layer drawn at least kObjectJoin wide on
    // cells of half that; its 8-connected pieces are the objects, numbered
    // in the order their first cell is met (rows from the lowest y, then x).
    // `is_model`: which beads are the model's (model_bead, or fewer: a
    // validator leaves out the support it judges).
    using BeadTest = std::function<bool(const Layer&, const Segment&)>;
    // `threads`: the layers drawn on that many threads (the same map).
    explicit ObjectMap(const LayerStack& stack, const BeadTest& is_model = model_bead, int threads = 1);
    int count() const { return count_; }
    // The object whose footprint holds (x, y), else the nearest within
    // `reach` mm of it (the first found, ring by ring); -1: none.
    int at(double x, double y, double reach = 0) const;

private:
    BitGrid grid_;
    std::vector<int> label_;
    int count_ = 0;
};

}  // namespace scaffold::layers
