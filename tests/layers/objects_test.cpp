// The objects on a plate (layers/objects): the pieces of the model's
// footprint over all layers; skirts are none.
#include <gtest/gtest.h>

#include "layers/objects.hpp"
#include "support/stacks.hpp"

using namespace scaffold;
using test::bead;

namespace {

// A 10 x 10 mm square of walls, lower left corner at (x, y).
void square(layers::Layer& l, double x, double y) {
    bead(l, x, y, x + 10, y, gcode::Role::ExternalPerimeter);
    bead(l, x + 10, y, x + 10, y + 10, gcode::Role::ExternalPerimeter);
    bead(l, x + 10, y + 10, x, y + 10, gcode::Role::ExternalPerimeter);
    bead(l, x, y + 10, x, y, gcode::Role::ExternalPerimeter);
}

}  // namespace

// Two squares 6 mm apart (a slicer's arrangement), a third whose walls
// come within 0.8 mm of the second's on its top layer only (one object
// with it: the footprint is over all layers), and a skirt round them all.
TEST(Objects, PiecesOfTheFootprintOverAllLayers) {
    const auto st = test::stack_of(
        10,
        [](int i, layers::Layer& l) {
            square(l, 10, 10);
            square(l, 26, 10);
            square(l, i == 9 ? 36.8 : 40, 10);
            if (i == 0) {
                bead(l, 5, 5, 60, 5, gcode::Role::Skirt);
                bead(l, 60, 5, 60, 25, gcode::Role::Skirt);
            }
        },
        {0, 0, 70, 30});
    const layers::ObjectMap map(st);
    EXPECT_EQ(map.count(), 2);
    const int a = map.at(15, 10), b = map.at(31, 20);
    EXPECT_GE(a, 0);
    EXPECT_GE(b, 0);
    EXPECT_NE(a, b);
    EXPECT_EQ(map.at(45, 10), b);  // the third square, joined on its top layer
    EXPECT_EQ(map.at(20, 5), -1);  // on the skirt, 5 mm below the first square's wall
    EXPECT_EQ(map.at(20, 7.5), -1);
    EXPECT_EQ(map.at(20, 7.5, 3.0), a);  // the nearest within 3 mm
    // The centre of a square is no bead's: the footprint is its walls.
    EXPECT_EQ(map.at(15, 15), -1);
    EXPECT_EQ(map.at(15, 15, 5.0), a);
    // A validator leaves its support out: a bar from the first square to the
    // second joins nothing.
    const auto with_bar = test::stack_of(
        10,
        [](int, layers::Layer& l) {
            square(l, 10, 10);
            square(l, 26, 10);
            bead(l, 20, 15, 26, 15, gcode::Role::Support);
        },
        {0, 0, 70, 30});
    EXPECT_EQ(layers::ObjectMap(with_bar).count(), 1);
    EXPECT_EQ(layers::ObjectMap(with_bar, [](const layers::Layer& l, const layers::Segment& s) {
                  return layers::model_bead(l, s) && s.role != gcode::Role::Support;
              }).count(),
              2);
}

// The layers drawn on several threads: the same objects, cell by cell. The
// join of the second and third squares is on one layer only, which one
// thread draws and the other does not.
TEST(Objects, TheSameMapOnAnyNumberOfThreads) {
    const auto st = test::stack_of(
        9,
        [](int i, layers::Layer& l) {
            square(l, 10, 10);
            square(l, 26, 10);
            square(l, i == 7 ? 36.8 : 40, 10);
        },
        {0, 0, 70, 30});
    const layers::ObjectMap one(st, layers::model_bead, 1);
    ASSERT_EQ(one.count(), 2);
    for (int threads : {2, 3, 16}) {
        SCOPED_TRACE(threads);
        const layers::ObjectMap many(st, layers::model_bead, threads);
        EXPECT_EQ(many.count(), one.count());
        for (double x = 0; x < 70; x += 0.25)
            for (double y = 0; y < 30; y += 0.25) ASSERT_EQ(many.at(x, y), one.at(x, y)) << x << ", " << y;
    }
}
