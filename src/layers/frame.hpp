#pragma once
// The plan's own frame. Rasters lie on a lattice of cells, and where a
// bead's edge falls between two cell centres decides which one it fills: a
// model moved 0.05 mm on the bed (a tenth of a cell at the default 0.1 mm
// resolution) got 10 % more support (bunny.prusaslicer25), and one copy on a
// plate a plan other than the model's alone on the bed. Planned with its
// lowest-leftmost bead end at the origin, to the micron (the files' three
// decimals), the same model plans the same wherever it stands.
#include <functional>

#include "layers/layer_stack.hpp"

namespace scaffold::layers {

// A translation in whole microns: (x, y) in the file is (x - dx, y - dy) in the frame.
struct Frame {
    long long dx_um = 0, dy_um = 0;
    double dx() const { return static_cast<double>(dx_um) / 1000.0; }
    double dy() const { return static_cast<double>(dy_um) / 1000.0; }
    bool identity() const { return dx_um == 0 && dy_um == 0; }
};

// The frame whose origin is the smallest x and the smallest y of the ends
// of the model's beads, rounded to the micron; the identity when there is
// no model. The model's beads: layers::model_bead (no skirt, wipe tower or
// purge line) and no support, the slicer's or any other; the validator,
// which knows what was added, passes its own test.
using FrameBead = std::function<bool(const Layer&, const Segment&)>;
Frame model_frame(const LayerStack& stack);
Frame model_frame(const LayerStack& stack, const FrameBead& is_model);

// A frame at the given point, rounded to the micron.
Frame frame_at(double x, double y);

// A box moved into the frame, or back out of it (`into` false).
Bounds move_bounds(const Bounds& b, const Frame& frame, bool into);

// Moves every bead (and the bounds) into the frame, or back out of it
// (`into` false). Ends are rounded to the micron on the way, so the same
// beads of two files, moved into their frames, are equal to the bit.
void move_stack(LayerStack& stack, const Frame& frame, bool into);

}  // namespace scaffold::layers
