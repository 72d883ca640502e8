#pragma once
// Writes small, valid PrusaSlicer-style G-code for tests: layers, typed
// extrusions with correct absolute E, travels with retraction, and a config
// block, so tests build their inputs instead of pasting G-code by hand.
#include <string>
#include <string_view>

namespace scaffold::testing {

class SynthGcode {
public:
    SynthGcode(double layer_height = 0.2, double width = 0.45, double filament_diameter = 1.75);

    // Starts a layer whose top is at z (writes ;LAYER_CHANGE/;Z:/;HEIGHT: and G1 Z).
    // Its height is z minus the last layer's z, or `height` when given (a
    // first layer over a raft's air gap: its beads are that thick).
    void layer(double z, double height = 0);
    void type(std::string_view prusa_role);  // e.g. "External perimeter", "Bridge infill"
    void width(double w);                    // writes ;WIDTH: and uses it for E
    void travel(double x, double y);         // retracts first when longer than 2 mm
    void extrude(double x, double y);        // straight bead from the current point
    // A closed loop around a rectangle, then solid lines across it.
    void rect_outline(double x0, double y0, double x1, double y1);
    void filled_rect(double x0, double y0, double x1, double y1);
    // A filled disc of radius r (concentric loops).
    void filled_disc(double cx, double cy, double r);
    // One closed loop: a regular polygon of `sides` around (cx, cy), as
    // slicers write circles (one move per side).
    void circle(double cx, double cy, double r, int sides = 96);
    void raw(std::string_view line);         // any extra line, verbatim

    // Layers of a filled box from z_from (exclusive) to z_to (inclusive) are
    // the caller's loop; this is the whole file with header and config.
    std::string str() const;

    double x() const { return x_; }
    double y() const { return y_; }
    double z() const { return z_; }

private:
    double e_per_mm() const;
    std::string body_;
    double h_, w_, fd_;
    double x_ = 0, y_ = 0, z_ = 0, e_ = 0, prev_z_ = 0;
};

// A print sliced with the slicer's own support on, as Simplify3D leaves it:
// a 10 x 10 mm base (layers 1-5), support (typed `support_role`) on it from
// layer 7, one layer of air above the base, up to layer 12, 0.3 mm from a
// wall of the model; a 6 x 6 mm sheet at layers 15-16 on the support's top
// across a two-layer contact gap; a tower keeps the layers going.
SynthGcode on_slicer_support(const char* support_role);

}  // namespace scaffold::testing
