#pragma once
// Exact copies on a plate. A slicer's instances of one object (PrusaSlicer's
// --duplicate, a plate of one model arranged N times) print the same beads,
// moved: one copy's support plan, moved, serves them all. Recognised from
// the beads alone and only where that is safe: the model's beads must form
// separate objects, and every layer's beads of each match the first's,
// moved, within a few microns (the file's three decimals). Anything else
// (Cura's meshes sliced one by one on the global infill grid, a different
// object, the slicer's own support) is no plate of copies.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "layers/layer_stack.hpp"
#include "layers/objects.hpp"

namespace scaffold::layers {

struct Offset {
    double dx = 0, dy = 0;
};

struct Copies {
    Bounds prototype;              // the first copy's box, beads' widths included
    std::vector<Offset> offsets;   // each copy's from the first: (0, 0) first, then by y, then x
    // The first copy's beads: per layer, their indices in Layer::segments
    // (boxes may overlap where a slicer nests copies by their outlines).
    std::vector<std::vector<std::uint32_t>> beads;
};

// Beads closer than about this belong to one object (copies standing
// nearer each other are one object: the plate is then planned whole).
inline constexpr double kCopyJoin = kObjectJoin;
// Largest difference, mm, between a bead of a copy moved onto the first and
// the first's matching bead.
inline constexpr double kCopyTolerance = 0.003;

// The plate's copies, or nullopt unless the model's beads form at least two
// objects, each an exact copy of the first (lowest, then leftmost). Skirts,
// wipe towers and purge lines belong to no copy; a file holding support of
// its own is no plate of copies. `why` (optional) says why not, for the log.
// The objects are compared with the first on `threads` threads (the same
// answer on any number).
std::optional<Copies> find_copies(const LayerStack& stack, std::string* why = nullptr, int threads = 1);
// The same with the plate's objects already found (ObjectMap of `stack`).
std::optional<Copies> find_copies(const LayerStack& stack, const ObjectMap& map, std::string* why = nullptr,
                                  int threads = 1);

// The first copy alone: its beads (nothing else), the same layers
// (heights, order) as `stack`, its box as bounds.
LayerStack first_copy(const LayerStack& stack, const Copies& copies);

// The layers as the first copy sees its surroundings from every copy's
// place at once: within `margin` mm of its box, each copy's neighbours (and
// the skirt, purge lines) moved by the offset that brings that copy onto the
// first. A support that keeps clear of this keeps clear of the plate when
// moved to any copy. Same layers (heights, order) as `stack`; its bounds are
// the window.
LayerStack seen_from_every_copy(const LayerStack& stack, const Copies& copies, double margin);

}  // namespace scaffold::layers
