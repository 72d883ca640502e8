#pragma once
// METHOD's rule (b), the part the detector and the validator share: a bead
// is held across a gap only where it *crosses* it. Each held end must be
// left across the edge of the footprint beneath, not along it: within 1 mm
// of the held end (or half the run, if shorter) the bead's distance from
// that footprint grows by at least half the length walked (it crosses the
// edge at 30 degrees or more). A wall running along the edge outside its
// reach -- the outer wall of a steep overhang -- crosses no gap.
//
// The piece walk itself (sample a straight piece, hold its spanned runs and
// short dangling ends) lives here once: the detector and the validator each
// call it. (toolpath/bar_check, the planner's check of its bars, still
// walks a bar its own way.)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "layers/layer_stack.hpp"
#include "layers/raster.hpp"

namespace scaffold::layers {

// Consecutive moves of one path turning by less than this from the piece's
// first move make one straight piece (METHOD.md's rule (b)).
inline constexpr double kStraightDeg = 10;
// How far a held end's test walks into the run (METHOD.md).
inline constexpr double kCrossingWalk = 1.0;
// A bead's unheld end this short is held (METHOD's rule (b)).
inline constexpr double kDanglingEnd = 1.0;

// One sample of a straight piece's centre line.
struct PieceSample {
    double x, y, s;     // position and arc length along the piece
    std::uint32_t seg;  // the caller's index of the segment it lies on
    bool held;          // by rule (a), then by the walk
};

// Distance in mm from (x, y) to the nearest set cell of `footprint` (to the
// cell's square, so 0 inside one), or `limit` when none is nearer.
double footprint_distance(const BitGrid& footprint, double x, double y, double limit);

// The walk for an unheld run `span` mm long between its held ends.
inline double crossing_walk(double span) { return span / 2 < kCrossingWalk ? span / 2 : kCrossingWalk; }

// Whether the bead leaves the held end (hx, hy) across the footprint's edge:
// at (px, py), `walked` mm along the run from it, its distance from the
// footprint has grown by at least walked / 2.
bool leaves_across(const BitGrid& footprint, double hx, double hy, double px, double py, double walked);

// Samples of a straight piece's centre line in order, each with x, y and its
// arc length s: the point `s` along it, between the samples around it.
template <class Sample>
void point_at(const std::vector<Sample>& p, double s, double& x, double& y) {
    std::size_t k = 1;
    while (k + 1 < p.size() && p[k].s < s) ++k;
    const Sample& a = p[k - 1];
    const Sample& b = p[k];
    const double t = b.s > a.s ? std::clamp((s - a.s) / (b.s - a.s), 0.0, 1.0) : 0.0;
    x = a.x + (b.x - a.x) * t;
    y = a.y + (b.y - a.y) * t;
}

// Whether the unheld run between held samples `a` and `b` (a < b) of a
// straight piece crosses the gap: it leaves both held ends across the
// footprint's edge (METHOD's rule (b)). The span limit is the caller's.
template <class Sample>
bool run_crosses(const BitGrid& footprint, const std::vector<Sample>& p, std::size_t a, std::size_t b) {
    const double walk = crossing_walk(p[b].s - p[a].s);
    double x, y;
    point_at(p, p[a].s + walk, x, y);
    if (!leaves_across(footprint, p[a].x, p[a].y, x, y, walk)) return false;
    point_at(p, p[b].s - walk, x, y);
    return leaves_across(footprint, p[b].x, p[b].y, x, y, walk);
}

// Appends segment `sg`'s centre-line samples, at most `step` apart, to the
// piece `p` (continuing its arc length; a segment after the first starts at
// the sample before), each held where `held` is set. Taken from the
// segment's float coordinates as the reader stores them, so every caller
// gets the validator's very samples.
void sample_segment(const Segment& sg, std::uint32_t seg, const BitGrid& held, double step, std::vector<PieceSample>& p);

// Whether a held sample lies within `reach` of the piece's end (at_end) or
// start, along it: the corner into a neighbouring piece is held there.
bool held_near_end(const std::vector<PieceSample>& p, bool at_end, double reach = kDanglingEnd);

// METHOD's rule (b) on one straight piece: marks held each unheld run that
// is held at both ends, at most `max_span` long and crossing the gap
// (run_crosses), and each dangling end of at most `dangling_end`. The runs
// left unheld are the piece's overhang.
void hold_runs(std::vector<PieceSample>& p, const BitGrid& footprint, double max_span,
               double dangling_end = kDanglingEnd);

// A coordinate as the validator reads it back: written with 3 decimals
// (splice), parsed, stored as a float (Segment).
inline float as_written(double v) { return static_cast<float>(std::round(v * 1000) / 1000); }

// A bead beneath a path, as the validator draws it: into the footprint
// (`rim`: not a skirt loop, which holds what lies on it but encloses no
// hole) and, grown by the reach, into what rule (a) holds.
struct BeadBeneath {
    float x0, y0, x1, y1, width;
    bool rim;
};

// The beads beneath drawn once, on the validator's lattice (make_grid's
// multiples of the cell), over a box: the footprint and what rule (a)
// holds, for every path walked over them inside it (less the crossing
// test's 4 mm search: kBeneathMargin).
inline constexpr double kBeneathMargin = 4.0;
class Beneath {
public:
    Beneath(const std::vector<BeadBeneath>& beads, double x0, double y0, double x1, double y1, double reach,
            double cell);
    // Whether every sample of a path of consecutive moves (its points as the
    // validator reads them back: `pts`, floats, inside the box less the
    // margin) is held by METHOD's rules (a) and (b) as the validator walks it
    // (check/printability): straight pieces within kStraightDeg of their
    // first move, holes the beads enclose, a corner held where the piece
    // before or after it is held within a dangling end of it (not at the
    // path's first point), then runs across gaps of at most `max_span` and
    // dangling ends. Rule (c) is not asked.
    bool path_held(const std::vector<std::array<float, 2>>& pts, double max_span,
                   double dangling_end = kDanglingEnd) const;

private:
    BitGrid footprint_, held_;
    mutable BitGrid filled_;  // the footprint with its holes filled, once asked
    mutable bool have_filled_ = false;
    double cell_;
};

// The same over the path's own box.
bool path_held(const std::vector<std::array<float, 2>>& pts, const std::vector<BeadBeneath>& beads, double reach,
               double cell, double max_span, double dangling_end = kDanglingEnd);

}  // namespace scaffold::layers
