#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>

#include "layers/layer_stack.hpp"
#include "plan/braces.hpp"
#include "plan/obstacles.hpp"
#include "plan/pillars.hpp"
#include "plan/stiffness.hpp"
#include "support/stacks.hpp"

using namespace scaffold;

namespace {

// A plain 2 mm column under a bar end at (50, 50), from the bed to z1.
plan::Column bar_column_at_50(double z1) {
    plan::Column c;
    c.x0 = c.x1 = 50;
    c.y0 = c.y1 = 50;
    c.z1 = c.hold_z = z1;
    c.radius = 1.0;
    c.top = plan::Top::Bridge;
    return c;
}

// 0.2 mm layers up to `layers`, a speck of model far away on each (the
// real Obstacles), and what `more` adds to layer i.
template <class More>
layers::LayerStack stack_with(int layers, More more) {
    return test::stack_of(
        layers,
        [&](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            more(i, l);
        },
        {-5, -5, 80, 80});
}

// A column's stiffness at `top` (one pillar, summed as METHOD sums it).
double stands_at(const std::vector<plan::Column>& chain, double top, const layers::LayerStack& st, const Settings& s) {
    plan::Scaffold sc;
    sc.columns = chain;
    const auto chains = plan::pillar_chains(sc);
    EXPECT_EQ(chains.size(), 1u);
    return chains.empty() ? 0.0 : 1 / plan::chain_compliance(chains[0], top, sc, st, s);
}

void outline(layers::Layer& l, double x0, double y0, double x1, double y1, gcode::Role role) {
    const float xs[5] = {float(x0), float(x1), float(x1), float(x0), float(x0)};
    const float ys[5] = {float(y0), float(y0), float(y1), float(y1), float(y0)};
    for (int k = 0; k < 4; ++k)
        l.segments.push_back({xs[k], ys[k], xs[k + 1], ys[k + 1], 0.45f, role, static_cast<std::uint32_t>(l.segments.size())});
}

// A hollow 20 mm box on 0.2 mm layers up to 4 mm, a skirt loop 5 mm around
// it on the first layer. Its outline printed as sparse infill (`role`) is a
// hole of the part's infill; printed as a wall, a cavity of the model.
layers::LayerStack hollow_box(gcode::Role role = gcode::Role::InternalInfill) {
    layers::LayerStack st;
    for (int i = 0; i < 20; ++i) {
        layers::Layer l;
        l.z = 0.2 * (i + 1);
        l.height = 0.2;
        l.below = i - 1;
        l.on_bed = i == 0;
        if (i == 0) outline(l, 95, 95, 125, 125, gcode::Role::Skirt);
        outline(l, 100, 100, 120, 120, role);
        st.layers.push_back(l);
    }
    st.bounds = {95, 95, 125, 125};
    return st;
}

}  // namespace

TEST(Obstacles, InsideThePartIsNoRoomOutsideTheSkirtLoopIs) {
    Settings s;
    const auto st = hollow_box();
    const plan::Obstacles obs(st, s);
    // 10 mm from every wall, but inside the part.
    EXPECT_FALSE(obs.disc_clear(10, 110, 110, 1.0));
    // Between the box and the skirt: clear (the skirt encloses nothing).
    EXPECT_TRUE(obs.disc_clear(0, 97.5, 110, 1.0));
    EXPECT_TRUE(obs.disc_clear(10, 90, 110, 1.0));
}

// A plan known to stay low (a plate of copies, its points found first)
// draws its obstacles only up to a height: above it every place on its grid
// is refused, below it each answer is the whole model's.
TEST(Obstacles, AboveTheDrawnHeightNothingIsClear) {
    Settings s;
    const auto st = hollow_box(gcode::Role::ExternalPerimeter);
    const plan::Obstacles all(st, s);
    const double solid_above = st.layers[10].z + 0.01;
    const plan::Obstacles low(st, s, 2, solid_above);
    ASSERT_EQ(low.layer_count(), all.layer_count());
    int clear_below = 0;
    for (int l = 0; l < all.layer_count(); ++l)
        for (double x : {90.0, 97.5, 101.0, 110.0, 130.0}) {
            SCOPED_TRACE(testing::Message() << "layer " << l << ", x " << x);
            if (st.layers[l].z > solid_above) {
                EXPECT_FALSE(low.disc_clear(l, x, 110, 1.0));
            } else {
                EXPECT_EQ(low.disc_clear(l, x, 110, 1.0), all.disc_clear(l, x, 110, 1.0));
                clear_below += all.disc_clear(l, x, 110, 1.0);
            }
        }
    EXPECT_GT(clear_below, 0);
}

TEST(Obstacles, ACavityOfTheModelIsRoom) {
    // The same box walled by perimeters alone (a dome's inside, a cabin):
    // room for a pillar 10 mm from every wall, and a pillar down to the bed
    // inside it, not standing on the outline of the hole.
    Settings s;
    auto st = hollow_box(gcode::Role::ExternalPerimeter);
    const plan::Obstacles inside(st, s);
    EXPECT_TRUE(inside.disc_clear(10, 110, 110, 1.0));
    EXPECT_FALSE(inside.disc_clear(10, 110, 100.5, 1.0));  // the wall itself
    EXPECT_EQ(inside.model_below(19, 110, 110, 1.0), -1);
    const plan::Obstacles infill(hollow_box(), s);
    EXPECT_EQ(infill.model_below(19, 110, 110, 1.0), 18);
}

TEST(Obstacles, InfillInsideAWallDoesNotFillTheCavityItWalls) {
    // A cabin's wall of two perimeters with infill between them, as a
    // slicer prints it: a short infill line's end lies on the inner
    // perimeter. Its end is no hole's seed: the room inside stays room (a
    // benchy's cabin was filled by such a dot, and a pillar stood on air).
    Settings s;
    auto st = hollow_box(gcode::Role::ExternalPerimeter);
    for (layers::Layer& l : st.layers) {
        outline(l, 100.9, 100.9, 119.1, 119.1, gcode::Role::Perimeter);
        const auto n = static_cast<std::uint32_t>(l.segments.size());
        l.segments.push_back({100.0f, 110.0f, 100.9f, 110.9f, 0.45f, gcode::Role::InternalInfill, n});
        l.segments.push_back({100.9f, 105.0f, 100.9f, 105.0f, 0.45f, gcode::Role::InternalInfill, n + 1});  // a dot
    }
    const plan::Obstacles obs(st, s);
    EXPECT_TRUE(obs.disc_clear(10, 110, 110, 1.0));
    EXPECT_EQ(obs.model_below(19, 110, 110, 1.0), -1);
    // A long infill line in the middle of the part still fills its holes.
    const plan::Obstacles infill(hollow_box(), s);
    EXPECT_FALSE(infill.disc_clear(10, 110, 110, 1.0));
}

TEST(Obstacles, NoPillarDownThroughAHollowPart) {
    Settings s;
    auto st = hollow_box();
    // A lid 2 mm wider than the box on the top layer: a point over the lid's
    // middle must not be held by a pillar standing inside the box.
    layers::Layer lid;
    lid.z = 4.2;
    lid.height = 0.2;
    lid.below = 19;
    for (double y = 98.2; y < 122; y += 0.4)
        lid.segments.push_back({98.2f, float(y), 121.8f, float(y), 0.45f, gcode::Role::SolidInfill,
                                static_cast<std::uint32_t>(lid.segments.size())});
    st.layers.push_back(lid);
    const plan::Obstacles obs(st, s);
    auto chain = plan::drop_pillar(110, 110, 20, plan::Top::Contact, st, obs, s);
    if (chain)
        for (const auto& c : *chain) {
            bool inside = c.x0 > 100 && c.x0 < 120 && c.y0 > 100 && c.y0 < 120;
            EXPECT_FALSE(inside) << "column at " << c.x0 << ", " << c.y0;
        }
}

// 0.2 mm layers to 20 mm, a speck of model far away, and a pillar to
// z = 10 at (50, 50) as the only trunk. Columns of the plain radius
// (--min-stiffness 0): the branches' geometry is under test here.
Settings without_standing() {
    Settings s;
    s.min_stiffness = 0;
    return s;
}
struct Trunks : ::testing::Test {
    Settings s = without_standing();
    const layers::LayerStack st = test::empty_stack(20, 80);
    const plan::Obstacles obs{st, s};
    const std::optional<std::vector<plan::Column>> trunk = plan::drop_pillar(50, 50, 50, plan::Top::Contact, st, obs, s);
    plan::Trunks with_steering(double steer) const {
        plan::Trunks t(st, steer);
        if (trunk) t.add(*trunk, st, s);
        return t;
    }
};

TEST_F(Trunks, ANearbyPointBranchesOffAnEarlierPillar) {
    ASSERT_TRUE(trunk);
    const plan::Trunks trunks = with_steering(plan::kBranchSteer);
    // A point 1.5 mm away over layer 70.
    auto alone = plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s);
    auto branch = plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s, &trunks);
    ASSERT_TRUE(alone && branch);
    EXPECT_EQ(alone->front().base, plan::Base::Bed);
    EXPECT_EQ(branch->front().base, plan::Base::Column);
    // It stands on the trunk below the trunk's top, its lowest loop within
    // the reach of the trunk's loop (0.8 x (0.2 tan 55 + 0.225) mm).
    const auto& low = branch->front();
    EXPECT_GT(low.z0, 1.0);
    EXPECT_LT(low.z0, 10.0 + 1e-6);
    EXPECT_LT(std::hypot(low.x0 - 50, low.y0 - 50), 0.8 * (0.2 * std::tan(55 * 3.14159265 / 180) + 0.225));
    // Its top is still where the point needs it.
    EXPECT_NEAR(branch->back().z1, st.layers[69].z, 1e-6);  // the layer under the point's
}

TEST_F(Trunks, WithoutSteeringOnlyAPillarRightAboveStandsOnIt) {
    ASSERT_TRUE(trunk);
    const plan::Trunks trunks = with_steering(0.0);
    // 1.5 mm away: its own way to the bed, straight down.
    auto apart = plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s, &trunks);
    ASSERT_TRUE(apart);
    EXPECT_EQ(apart->front().base, plan::Base::Bed);
    for (const auto& c : *apart) EXPECT_EQ(c.x0, 51.5);
    // 0.2 mm off the trunk's axis, one layer over its tip: it stands on the
    // tip, a column of one layer, vertical.
    auto above = plan::drop_pillar(50.2, 50, 51, plan::Top::Contact, st, obs, s, &trunks);
    ASSERT_TRUE(above);
    ASSERT_EQ(above->size(), 1u);
    EXPECT_EQ(above->front().base, plan::Base::Column);
    EXPECT_NEAR(above->front().z0, st.layers[49].z, 1e-6);
    EXPECT_EQ(above->front().x0, 50.2);
    EXPECT_EQ(above->front().x1, 50.2);
}

// The same columns, field by field.
void expect_same_chain(const std::optional<std::vector<plan::Column>>& a,
                       const std::optional<std::vector<plan::Column>>& b) {
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) return;
    ASSERT_EQ(a->size(), b->size());
    for (std::size_t i = 0; i < a->size(); ++i) {
        const plan::Column &p = (*a)[i], &q = (*b)[i];
        EXPECT_EQ(std::tie(p.x0, p.y0, p.z0, p.x1, p.y1, p.z1, p.radius, p.taper, p.max_radius, p.foot_radius),
                  std::tie(q.x0, q.y0, q.z0, q.x1, q.y1, q.z1, q.radius, q.taper, q.max_radius, q.foot_radius))
            << "piece " << i;
        EXPECT_EQ(p.base, q.base) << "piece " << i;
    }
}

// Walks down kept (DescentCache) answer for the next trunks only where no
// trunk comes within reach of them: a point 1.5 mm from the trunk branches
// off it as without the cache (its walk kept from a plan without the trunk
// is not taken), one 10 mm away takes its kept walk, the same column.
TEST_F(Trunks, AWalkKeptHoldsOnlyWhereNoTrunkComesNear) {
    ASSERT_TRUE(trunk);
    plan::DescentCache cache;
    plan::Trunks none(st, plan::kBranchSteer);
    none.keep_descents(&cache);
    const auto near_alone = plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s, &none);
    const auto far_alone = plan::drop_pillar(60, 50, 70, plan::Top::Contact, st, obs, s, &none);
    EXPECT_EQ(cache.hits, 0);
    const long long walked = cache.misses;
    EXPECT_GT(walked, 0);
    // Asked again with no trunks: every walk from the cache, the same columns.
    expect_same_chain(plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s, &none), near_alone);
    EXPECT_EQ(cache.misses, walked);
    EXPECT_GT(cache.hits, 0);

    plan::Trunks with_trunk = with_steering(plan::kBranchSteer);
    const auto near_fresh = plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s, &with_trunk);
    const auto far_fresh = plan::drop_pillar(60, 50, 70, plan::Top::Contact, st, obs, s, &with_trunk);
    ASSERT_TRUE(near_fresh && near_alone);
    EXPECT_EQ(near_fresh->front().base, plan::Base::Column);
    EXPECT_EQ(near_alone->front().base, plan::Base::Bed);
    with_trunk.keep_descents(&cache);
    const long long misses = cache.misses;
    expect_same_chain(plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s, &with_trunk), near_fresh);
    EXPECT_GT(cache.misses, misses);  // walked again: the trunk is within reach
    const long long hits_near = cache.hits;
    expect_same_chain(plan::drop_pillar(60, 50, 70, plan::Top::Contact, st, obs, s, &with_trunk), far_fresh);
    expect_same_chain(far_fresh, far_alone);
    EXPECT_GT(cache.hits, hits_near);  // 10 mm off: the walk kept
}

TEST(PlanPillars, PointsStackedUpASlopeShareOneColumn) {
    Settings s = without_standing();
    const layers::LayerStack st = test::empty_stack(20, 80);
    const plan::Obstacles obs(st, s);
    // A slope's edge: a point on each of ten layers, 0.1 mm further out each
    // time (as a sliver per layer gives). Listed top first: the planner must
    // still put the lower first.
    overhang::SupportPoints pts;
    for (int k = 9; k >= 0; --k)
        pts.points.push_back({50 + 0.1 * k, 50, st.layers[39 + k].z, 40 + k});
    const plan::Scaffold plan = plan::plan_pillars(pts, st, obs, s);
    EXPECT_TRUE(plan.dropped_points.empty());
    int on_bed = 0;
    for (const auto& c : plan.columns) {
        on_bed += c.base == plan::Base::Bed;
        EXPECT_EQ(c.x0, c.x1);  // simple pillars do not lean
    }
    EXPECT_EQ(on_bed, 1);
    EXPECT_EQ(plan.columns.size(), 10u);
}

// METHOD's Standing rule: a column stands on a trunk only where the trunk
// was sized for what then stands on it. The trunk to z = 10 was sized for
// its own top; a point over layer 70 (z 14) is higher, so it goes down on
// its own, and the trunk's width at its foot is what its own top needs.
// The pillar under a point over layer 50 at (50, 50), as a trunk to branch
// off (steering as the scaffold method does).
struct TrunkAt50 {
    std::optional<std::vector<plan::Column>> trunk;
    plan::Trunks trunks;
    TrunkAt50(const layers::LayerStack& st, const plan::Obstacles& obs, const Settings& s)
        : trunk(plan::drop_pillar(50, 50, 50, plan::Top::Contact, st, obs, s)), trunks(st, plan::kBranchSteer) {
        if (trunk) trunks.add(*trunk, st, s);
    }
};

TEST(PlanPillars, AColumnStandsOnlyOnATrunkSizedForIt) {
    Settings s;  // --min-stiffness 2
    const layers::LayerStack st = test::empty_stack(20, 80);
    const plan::Obstacles obs(st, s);
    const TrunkAt50 t(st, obs, s);
    const auto& [trunk, trunks] = t;
    ASSERT_TRUE(trunk);
    const auto branch = plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, s, &trunks);
    ASSERT_TRUE(branch);
    EXPECT_EQ(branch->front().base, plan::Base::Bed);
    // 10 mm of 2 mm ring is stiff enough (3 E I / h^3 = 3 x 3500 x pi x
    // 0.775^3 x 0.45 / 1000 = 6.9 N/mm > 2.5): no taper.
    EXPECT_EQ(trunk->front().taper, 0.0);
    Settings off = without_standing();
    const auto plain = plan::drop_pillar(51.5, 50, 70, plan::Top::Contact, st, obs, off, &trunks);
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->front().base, plan::Base::Column);
}

TEST(PlanPillars, ContactIsTheTopTwoLayersWhateverTheFloatRounding) {
    plan::Column c;
    c.contact_z = 33.6f;  // 33.599998
    EXPECT_TRUE(plan::in_contact(c, 33.6f, 0.2));
    EXPECT_TRUE(plan::in_contact(c, 33.4f, 0.2));
    EXPECT_FALSE(plan::in_contact(c, 33.2f, 0.2));  // 33.200001: once taken for the contact
    c.contact_z = 0;  // under a bridge end with no tip
    EXPECT_FALSE(plan::in_contact(c, 33.6f, 0.2));
}

// A solid slab (infill lines along x, 0.45 mm apart) to z 4 with a slot
// 1.35 mm across (bead edges at y 109.45 and 110.8) along its middle, open at
// both ends, and nothing above it up to a point at z 8 over (110, 110). The
// pillar under the point lands on the slab. Right under the point its bottom
// loop would cross the slot, held by rule (b) (each side over it held at an
// end), yet lie mostly over the slot: METHOD's Standing rule counts no base
// there (under 30 % of its cells over the model), and a column on it would
// float. It lands beside the slot instead, within a tip's reach of the point.
TEST(Obstacles, APillarOverANarrowSlotLandsBesideIt) {
    Settings s;
    const layers::LayerStack st = test::stack_of(
        40,
        [](int i, layers::Layer& l) {
            if (i < 20)
                for (double y = 100.225; y < 120; y += 0.45)
                    if (std::abs(y - 110) > 0.5 + 0.225) test::bead(l, 100, y, 120, y);
            if (l.segments.empty()) test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
        },
        {-5, -5, 130, 130});
    const plan::Obstacles obs(st, s);
    EXPECT_TRUE(obs.disc_clear(19, 110, 110, 0.4));  // the slot is open
    auto chain = plan::drop_pillar(110, 110, 39, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain.has_value());
    ASSERT_FALSE(chain->empty());
    const plan::Column& base = chain->front();
    EXPECT_EQ(base.base, plan::Base::Model);
    EXPECT_NEAR(base.z0, 4.0, 1e-6);
    const double r = plan::column_radius_at(base, st.layers[20].z, s);
    EXPECT_TRUE(plan::loop_stands_on_model(base.x0, base.y0, r, 20, st, s));
    EXPECT_FALSE(plan::loop_stands_on_model(110, 110, r, 20, st, s));
    EXPECT_LE(std::hypot(base.x0 - 110, base.y0 - 110), 1.0 + 1e-9);
    EXPECT_GT(std::abs(base.y0 - 110.125), 0.675);  // its centre off the slot
}

// METHOD's Standing rule: a column passing a narrow place keeps its taper
// above and below it and is only as narrow as the place allows there. A
// point at z 40 over (50, 50); between z 10.2 and 12 two walls stand 2.5 mm
// either side of it (their beads' edges 2.275 mm away), too close for the
// widened column (2 mm plus the taper for 40 mm, about 1.2 mm more by then),
// and no step aside gets it out of the slot. The column goes straight down
// with its full taper, capped by the walls on those layers only, and a
// little more taper everywhere else where the cap leaves it short of the
// rule (0.0573 against 0.0551: the longest levers are below the walls).
TEST(PlanPillars, AColumnIsAsWideAsTheRoomOnEachLayer) {
    Settings s;  // --min-stiffness 2
    const layers::LayerStack st = test::stack_of(
        200,
        [](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (i >= 50 && i < 60) {
                test::bead(l, 47.5, 40, 47.5, 60, gcode::Role::Perimeter);
                test::bead(l, 52.5, 40, 52.5, 60, gcode::Role::Perimeter);
            }
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    const auto chain = plan::drop_pillar(50, 50, 199, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain);
    ASSERT_FALSE(chain->empty());
    EXPECT_EQ(chain->front().base, plan::Base::Bed);
    const double full = plan::taper_for(s.pillar_radius, chain->front().hold_z, plan::target_stiffness(s), 0,
                                        s.support_width, s.modulus);
    ASSERT_GT(full, 0.02);
    const double taper = chain->front().taper;
    EXPECT_GE(taper, full);
    EXPECT_LT(taper, 1.1 * full);
    auto radius_at = [&](double z) {
        for (const plan::Column& c : *chain)
            if (z > c.z0 + 1e-6 && z <= c.z1 + 1e-6) {
                EXPECT_EQ(c.x0, 50);  // straight down: no step aside
                EXPECT_EQ(c.taper, taper);
                return plan::column_radius_at(c, z, s);
            }
        ADD_FAILURE() << "no piece at z " << z;
        return 0.0;
    };
    plan::Scaffold sc;
    sc.columns = *chain;
    ASSERT_EQ(plan::pillar_chains(sc).size(), 1u);
    EXPECT_GE(1 / plan::chain_compliance(plan::pillar_chains(sc)[0], chain->front().hold_z, sc, st, s),
              s.min_stiffness);
    // Straight down, so a loop's radius may change by the whole shift limit
    // (the taper's own change per layer aside).
    const double step = plan::loop_shift_limit(0.2, s) + taper * 0.2 + 1e-9;
    double below = radius_at(st.layers[0].z);
    for (int l = 1; l < 180; ++l) {  // below the tip
        const double z = st.layers[l].z, r = radius_at(z);
        // Clear of the walls, never under the plain radius, and a loop rests
        // on the one below.
        EXPECT_TRUE(obs.disc_clear(l, 50, 50, r + s.xy_gap)) << "z " << z;
        EXPECT_GE(r, s.pillar_radius - 1e-9);
        EXPECT_LE(std::abs(r - below), step) << "z " << z;
        below = r;
    }
    // Full width away from the walls: 5 mm under them, and from 5 mm above.
    const double hold = chain->front().hold_z;
    EXPECT_NEAR(radius_at(5.0), s.pillar_radius + taper * (hold - 5.0), 1e-6);
    EXPECT_NEAR(radius_at(17.0), s.pillar_radius + taper * (hold - 17.0), 1e-6);
    EXPECT_LT(radius_at(11.0), 2.275 - s.xy_gap + s.resolution);  // (the raster's edge)
    EXPECT_LT(radius_at(11.0), s.pillar_radius + full * (hold - 11.0) - 0.3);
}

// Another thread's Obstacles share the model rasters (a plate's largest
// part: bunny x 16 took 1160 MB on one thread, 1885 MB on two with a copy)
// and keep caches of their own: the same answers, asked in any order.
TEST(Obstacles, AnotherSharesTheRastersAndAnswersAlike) {
    Settings s;
    const auto st = hollow_box(gcode::Role::ExternalPerimeter);
    const plan::Obstacles obs(st, s);
    const std::unique_ptr<const plan::Obstacles> other = obs.another();
    ASSERT_EQ(other->layer_count(), obs.layer_count());
    int blocked = 0, clear = 0, skirt_room = 0;
    for (int l = 0; l < obs.layer_count(); ++l) {
        EXPECT_EQ(&other->footprint(l), &obs.footprint(l)) << l;
        EXPECT_EQ(other->layer_z(l), obs.layer_z(l));
        EXPECT_EQ(other->model_below(l, 110, 110, 1.0), obs.model_below(l, 110, 110, 1.0));
        for (double x = 94; x <= 126; x += 0.7)
            for (double r : {0.5, 1.0, 2.5}) {
                const bool a = obs.disc_clear(l, x, 100.3, r);
                EXPECT_EQ(other->disc_clear(l, x, 100.3, r), a) << l << " " << x << " " << r;
                EXPECT_EQ(other->line_clear(l, x, 90, x, 130), obs.line_clear(l, x, 90, x, 130));
                (a ? clear : blocked)++;
                // Beside the skirt (layer 0, x 95) too: room_clear gives
                // back only the skirt's share of the gap, in either copy.
                const bool room = obs.room_clear(l, x, 100.3, r);
                EXPECT_EQ(other->room_clear(l, x, 100.3, r), room) << l << " " << x << " " << r;
                EXPECT_TRUE(room || !a) << l << " " << x << " " << r;  // clear is room
                skirt_room += room && !a;
            }
    }
    EXPECT_GT(blocked, 0);
    EXPECT_GT(clear, 0);
    EXPECT_GT(skirt_room, 0);  // discs that only the skirt's own gap lets through
}

// Rasterised on three threads, the layers are the same, skirt and all: the
// footprints cell for cell, and the skirt's room beside the part.
TEST(Obstacles, BuiltOnThreadsTheRastersAreTheSame) {
    Settings s;
    const auto st = hollow_box(gcode::Role::ExternalPerimeter);
    const plan::Obstacles one(st, s, 1), three(st, s, 3);
    ASSERT_EQ(three.layer_count(), one.layer_count());
    std::size_t cells = 0;
    for (int l = 0; l < one.layer_count(); ++l) {
        const layers::BitGrid &a = one.footprint(l), &b = three.footprint(l);
        ASSERT_TRUE(a.same_shape(b)) << l;
        for (int j = 0; j < a.height(); ++j)
            for (int i = 0; i < a.width(); ++i) {
                ASSERT_EQ(a.get(i, j), b.get(i, j)) << l << " " << i << " " << j;
                cells += a.get(i, j);
            }
        for (double x = 94; x <= 126; x += 0.7)
            EXPECT_EQ(three.room_clear(l, x, 100.3, 1.0), one.room_clear(l, x, 100.3, 1.0)) << l << " " << x;
    }
    EXPECT_GT(cells, 0u);
}

// A column widened for the Standing rule over a post's foot narrower than
// its bottom loop (the shelf's): its bottom loop is narrowed to what lies on
// the post all round and the loops above widen again, so it keeps the full
// taper (for its height above the post); it used to be turned away there and
// fall back to part of it. A round post of radius 1.2 mm to z 2.0, a 6 mm
// sheet at z 30 over it, nothing else.
TEST(Obstacles, AWidenedColumnNarrowsItsFootOnASmallTop) {
    Settings s;
    const layers::LayerStack st = test::stack_of(
        150,
        [](int i, layers::Layer& l) {
            if (l.z <= 2.0 + 1e-9)
                for (double r : {1.0, 0.6, 0.2})  // bead centres: the post's edge at 1.2
                    for (int k = 0; k < 48; ++k) {
                        const double a = k * std::numbers::pi / 24, b = (k + 1) * std::numbers::pi / 24;
                        test::bead(l, 100 + r * std::cos(a), 100 + r * std::sin(a), 100 + r * std::cos(b),
                                   100 + r * std::sin(b), gcode::Role::ExternalPerimeter);
                    }
            if (i == 149)
                for (double y = 97; y <= 103 + 1e-9; y += 0.4) test::bead(l, 97, y, 103, y);
        },
        {97, 97, 103, 103});
    const plan::Obstacles obs(st, s);
    const auto chain = plan::drop_pillar(100, 100, 149, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain && !chain->empty());
    const plan::Column& foot = chain->front();
    EXPECT_EQ(foot.base, plan::Base::Model);
    EXPECT_NEAR(foot.z0, 2.0, 1e-6);
    const double full_taper = plan::taper_for(foot.radius, foot.hold_z - foot.z0, plan::target_stiffness(s), 0,
                                              s.support_width, s.modulus);
    EXPECT_GT(full_taper, 0.01);
    EXPECT_NEAR(foot.taper, full_taper, 1e-9);
    // Its bottom loop (at z 2.2) lies on the post, narrower than the taper
    // would make it: its centre line (0.225 inside its outer radius) within
    // rule (a)'s reach (0.2 tan 55 = 0.286) of the post's edge at 1.225; the
    // loops above widen again.
    auto radius_at = [&](double z) {
        for (const plan::Column& c : *chain)
            if (z > c.z0 + 1e-6 && z <= c.z1 + 1e-6) return plan::column_radius_at(c, z, s);
        return -1.0;
    };
    const double bottom = radius_at(2.2);
    EXPECT_LE(bottom - 0.225, 1.225 + 0.2 * std::tan(55 * std::numbers::pi / 180));
    EXPECT_LT(bottom, foot.radius + foot.taper * (foot.hold_z - 2.2) - 0.05);
    EXPECT_GT(radius_at(4.0), bottom + 0.05);
}

// The same post, with layers as Cura prints them over a raft at 0.3 mm:
// the first above the post 0.3 thick, the second only 0.08 (Cura lowers
// every layer after the first by 0.22), then 0.3 again. The loops widen
// from the narrowed bottom loop only as far as each layer's own height
// lets a loop step out: 0.271 mm over the 0.08 mm layer, not the 0.52 a
// 0.3 mm layer allows.
TEST(Obstacles, ANarrowedFootWidensOnlyAsAThinLayerHolds) {
    Settings s;
    s.layer_height = 0.3;
    std::vector<double> zs;
    for (double z = 0.2; z <= 2.0 + 1e-9; z += 0.2) zs.push_back(z);
    zs.push_back(2.3);
    for (double z = 2.38; z <= 30.0 + 1e-9; z += 0.3) zs.push_back(z);
    const layers::LayerStack st = test::stack_at(
        zs,
        [&](int i, layers::Layer& l) {
            if (l.z <= 2.0 + 1e-9)
                for (double r : {1.0, 0.6, 0.2})
                    for (int k = 0; k < 48; ++k) {
                        const double a = k * std::numbers::pi / 24, b = (k + 1) * std::numbers::pi / 24;
                        test::bead(l, 100 + r * std::cos(a), 100 + r * std::sin(a), 100 + r * std::cos(b),
                                   100 + r * std::sin(b), gcode::Role::ExternalPerimeter);
                    }
            if (i + 1 == static_cast<int>(zs.size()))
                for (double y = 97; y <= 103 + 1e-9; y += 0.4) test::bead(l, 97, y, 103, y);
        },
        {97, 97, 103, 103});
    const plan::Obstacles obs(st, s);
    const auto chain = plan::drop_pillar(100, 100, static_cast<int>(zs.size()) - 1, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain && !chain->empty());
    EXPECT_EQ(chain->front().base, plan::Base::Model);
    auto radius_at = [&](double z) {
        for (const plan::Column& c : *chain)
            if (z > c.z0 + 1e-6 && z <= c.z1 + 1e-6) return plan::column_radius_at(c, z, s);
        return -1.0;
    };
    const double bottom = radius_at(2.3), second = radius_at(2.38);
    ASSERT_GT(bottom, 0);
    EXPECT_GT(second, bottom);  // it does widen
    EXPECT_LE(second - bottom, plan::loop_shift_limit(0.08, s) + 1e-9);
    EXPECT_GE(radius_at(2.68), second - 1e-9);
}

// A point in a crotch of the model (an elephant's leg meeting its belly),
// 25 mm up: solid model either side of it closes in towards its top, its
// inner edges 1.0 + 0.25 dz mm from the point, dz below the layer under
// the point (up to 4 mm), and open below. The plain tip (0.5 mm at the
// contact, the full 1 mm 2 mm lower, with the 0.5 mm gap: 1.5 mm of room
// asked where 1.5 less the raster's edge is left), the thinner columns
// and every place within 3 mm find no way down (the build before this
// neck planned nothing here). A neck twice as long (4 mm) fits, and below
// the walls the column is as wide as the rule asks.
TEST(PlanPillars, ALongerNeckReachesIntoACrotchAndTheColumnStaysWideBelow) {
    Settings s;
    constexpr int kTop = 125;  // the point's layer, z 25.2
    const layers::LayerStack st = test::stack_of(
        kTop + 1,
        [](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            const double dz = 0.2 * (kTop - 1 - i);  // below the layer under the point
            if (i == kTop) test::bead(l, 46, 50, 54, 50);
            if (i < kTop && dz <= 4.0) {
                // Solid either side, beads 0.45 mm apart from the inner edge out.
                for (double e = 1.0 + 0.25 * dz + 0.225; e < 10; e += 0.45) {
                    test::bead(l, 50 - e, 40, 50 - e, 60);
                    test::bead(l, 50 + e, 40, 50 + e, 60);
                }
            }
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    const auto chain = plan::drop_pillar(50, 50, kTop, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain);
    ASSERT_FALSE(chain->empty());
    const plan::Column& top = chain->back();
    EXPECT_EQ(chain->front().base, plan::Base::Bed);
    EXPECT_GT(top.neck, s.tip_length);
    EXPECT_DOUBLE_EQ(top.radius, s.pillar_radius);
    EXPECT_GT(top.taper, 0);
    // Clear of the walls on every layer they stand on.
    for (const plan::Column& c : *chain)
        for (int l = 0; l < kTop; ++l) {
            const double z = st.layers[l].z;
            if (z <= c.z0 + 1e-6 || z > c.z1 + 1e-6) continue;
            double x, y;
            plan::column_centre_at(c, z, x, y);
            EXPECT_TRUE(obs.disc_clear(l, x, y, plan::column_radius_at(c, z, s) + plan::clearance_at(c, z, s)))
                << "z " << z;
        }
    // Stiff as the rule asks: at least 2 N/mm at its top, where the thin
    // fallback (1 mm across, 12.6 mm) would stand about 0.2.
    plan::Scaffold sc;
    sc.columns = *chain;
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_GE(1 / plan::chain_compliance(chains[0], top.z1, sc, st, s), s.min_stiffness);
}

// A tip's column found plain and thin (a copy of a plate 6 mm off, a slot at
// its top) stands by the Standing rule once widened along the same way down
// where there is room. By hand: a single-wall ring of 0.6 mm outer radius
// (centre line 0.375 mm, 0.45 mm wall), E I = 3500 pi 0.45 0.375^3 =
// 260.93 N mm^2, 19.6 mm from the bed to its top: over the 98 layers, each
// (0.2 k, 0.2 (k + 1)) below the top, the integral of h^2 dh / E I, summed:
// 0.008 sum (k + 1/2)^2 (k = 0..97) = 0.008 (308945 + 4753 + 24.5) =
// 2509.78 mm^3, / 260.93 = 9.619 mm/N: 0.104 N/mm.
TEST(PlanPillars, AThinColumnWidensBelowWhereItIsSqueezed) {
    Settings s;  // --min-stiffness 2
    constexpr int kTop = 97;  // z 19.6
    const layers::LayerStack st = test::stack_of(
        kTop + 3,
        [](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (i >= 85) {  // walls 2.8 mm apart from z 17.2 up
                test::bead(l, 48.6, 40, 48.6, 60, gcode::Role::Perimeter);
                test::bead(l, 51.4, 40, 51.4, 60, gcode::Role::Perimeter);
            }
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    plan::Column plain;
    plain.x0 = plain.x1 = 50;
    plain.y0 = plain.y1 = 50;
    plain.z0 = 0;
    plain.z1 = st.layers[kTop].z;
    plain.radius = 0.6;
    plain.hold_z = plain.z1;
    plain.base = plan::Base::Bed;
    std::vector<plan::Column> chain{plain};
    auto stiffness = [&](const std::vector<plan::Column>& c) {
        plan::Scaffold sc;
        sc.columns = c;
        const auto chains = plan::pillar_chains(sc);
        EXPECT_EQ(chains.size(), 1u);
        return 1 / plan::chain_compliance(chains[0], plain.z1, sc, st, s);
    };
    EXPECT_NEAR(stiffness(chain), 1 / 9.619, 0.0005);
    ASSERT_TRUE(plan::widen_column(chain, st, obs, s));
    const double full = plan::taper_for(0.6, plain.z1, plan::target_stiffness(s), 0, s.support_width, s.modulus);
    ASSERT_GT(full, 0.03);
    EXPECT_GE(stiffness(chain), s.min_stiffness);
    EXPECT_EQ(chain.front().base, plan::Base::Bed);
    EXPECT_EQ(chain.front().z0, 0);
    double below = 0;
    for (int l = 0; l <= kTop; ++l) {
        const double z = st.layers[l].z;
        const auto piece = std::find_if(chain.begin(), chain.end(), [&](const plan::Column& c) {
            return z > c.z0 + 1e-6 && z <= c.z1 + 1e-6;
        });
        ASSERT_NE(piece, chain.end()) << "z " << z;
        double x, y;
        plan::column_centre_at(*piece, z, x, y);
        EXPECT_EQ(x, 50);  // the same way down
        EXPECT_EQ(y, 50);
        const double r = plan::column_radius_at(*piece, z, s);
        EXPECT_TRUE(obs.disc_clear(l, x, y, r + s.xy_gap)) << "z " << z;
        EXPECT_GE(r, 0.6 - 1e-9);
        if (z > 17.1) {  // squeezed between the walls (their beads' edges 1.175 mm off)
            EXPECT_LE(r, 1.175 - s.xy_gap + s.resolution) << "z " << z;
        }
        if (z < 12) {  // the full taper where there is room, the lever longest
            EXPECT_NEAR(r, 0.6 + full * (plain.z1 - z), 1e-9) << "z " << z;
        }
        if (l > 0) {  // each loop rests on the one below it
            EXPECT_LE(std::abs(r - below), plan::loop_shift_limit(0.2, s) + 1e-9) << "z " << z;
        }
        below = r;
    }
    // Already standing: left as it is.
    std::vector<plan::Column> again = chain;
    EXPECT_FALSE(plan::widen_column(again, st, obs, s));
}

// The bridge search's question about a bar end, answered from the places
// where straight descents were first blocked, is drop_pillar's own answer
// everywhere. The scene: a block whose top holds columns (z 6), above it a
// model bar too narrow to land on (z 9 to 10), a wall leaning out 0.1 mm a
// layer and a slot; over a grid of places, bar ends under every layer from
// z 6.4 to 20, highest first and then lowest first, so that a place is
// asked from above and below the bar (blocked first at different layers,
// with different answers) and within a tip's length of what blocks it.
TEST(PlanPillars, BarEndsStandExactlyWhereTheirPillarsDo) {
    Settings s;
    constexpr int kLayers = 100;  // z 0.2 .. 20
    const layers::LayerStack st = test::stack_of(
        kLayers,
        [](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (i < 30)
                for (double y = 40.225; y < 52; y += 0.45) test::bead(l, 40, y, 52, y);
            if (i >= 44 && i < 50) test::bead(l, 38, 46, 54, 46);
            if (i < 60) test::bead(l, 54 + 0.1 * i, 36, 54 + 0.1 * i, 58);
            if (i < 80) {
                test::bead(l, 42, 54, 50, 54);
                test::bead(l, 42, 55.6, 50, 55.6);
            }
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    plan::BarEndAnswers known;
    int stands = 0, falls = 0;
    for (bool down : {true, false})
        for (int k = 0; k < 64; ++k) {
            const int layer = down ? 95 - k : 32 + k;
            for (double x = 38.3; x < 60; x += 1.1)
                for (double y = 38.1; y < 58; y += 1.1) {
                    const bool want = plan::drop_pillar(x, y, layer, plan::Top::Bridge, st, obs, s, nullptr,
                                                        plan::TipPlaces::Any, false)
                                          .has_value();
                    ASSERT_EQ(plan::bar_end_stands(x, y, layer, st, obs, s, known), want)
                        << "at (" << x << ", " << y << ") under layer " << layer;
                    (want ? stands : falls)++;
                }
        }
    // Both answers were given, and many places kept.
    EXPECT_GT(stands, 1000);
    EXPECT_GT(falls, 1000);
    EXPECT_GT(known.size(), 100u);
}

// METHOD's Standing rule: a column's bottom loop is a base on the model when
// 30 % of its cells lie over the model's footprint below (35 % asked). A
// loop of radius 1 (its bead 0.45 wide: the ring between 0.55 and 1 mm from
// its centre, 2.19 mm^2) over walls 0.45 wide, their shares of the ring
// integrated by hand:
// - walls 1.3 mm apart, the loop centred between them: 55 %;
// - the same walls, the loop 0.42 mm off the middle (walls 1.07 mm to one
//   side and 0.23 to the other, a Kiri:Moto benchy's floating column): 25 %;
// - one wall through the loop's centre: 19 %;
// - a solid top: all of it.
TEST(PlanPillars, ALoopStandsOnTheModelWhereThirtyPercentOfItIsOverIt) {
    const Settings s;
    auto walls = [](std::vector<double> xs) {
        return test::stack_of(
            14,
            [xs](int i, layers::Layer& l) {
                if (i < 10)
                    for (double x : xs) test::bead(l, x, 40, x, 60, gcode::Role::Perimeter);
            },
            {30, 30, 70, 70});
    };
    const layers::LayerStack slot = walls({49.35, 50.65});
    EXPECT_TRUE(plan::loop_stands_on_model(50, 50, 1.0, 10, slot, s));
    EXPECT_FALSE(plan::loop_stands_on_model(50.42, 50, 1.0, 10, slot, s));
    EXPECT_FALSE(plan::loop_stands_on_model(50, 50, 1.0, 10, walls({50}), s));
    std::vector<double> solid;
    for (double x = 45.225; x < 55; x += 0.45) solid.push_back(x);
    EXPECT_TRUE(plan::loop_stands_on_model(50, 50, 1.0, 10, walls(solid), s));
    // The layers within two nominal heights below only: the top (z 2.0) is
    // two layers under layer 11 (z 2.4), three under layer 12 (z 2.6).
    EXPECT_TRUE(plan::loop_stands_on_model(50, 50, 1.0, 11, walls(solid), s));
    EXPECT_FALSE(plan::loop_stands_on_model(50, 50, 1.0, 12, walls(solid), s));
}

// A tip whose column, where first found, is short of the Standing rule
// looks on around its point. A point at z 30 over (50, 50); up to z 15 two
// walls run from y 30 to 51, 2 mm either side of it (their beads' edges
// 1.775 mm off). Straight down, the column fits at 1 mm but its taper is
// capped at 1.3 mm between the walls, where its lever is longest: 0.707 N/mm
// (the place first found, kept when the tip looks no further). A place
// 0.75 mm on, towards the walls' end, stands (2.39).
TEST(PlanPillars, ATipShortOfTheRuleWhereFirstFoundLooksOnAroundItsPoint) {
    Settings s;  // --min-stiffness 2
    constexpr int kOverhang = 149;  // z 30
    const layers::LayerStack st = test::stack_of(
        kOverhang + 1,
        [](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (i < 75) {
                test::bead(l, 48.0, 30, 48.0, 51, gcode::Role::Perimeter);
                test::bead(l, 52.0, 30, 52.0, 51, gcode::Role::Perimeter);
            }
            if (i == kOverhang)
                for (double y = 40.225; y < 60; y += 0.45) test::bead(l, 40, y, 60, y);
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    const auto chain = plan::drop_pillar(50, 50, kOverhang, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain);
    ASSERT_FALSE(chain->empty());
    plan::Scaffold sc;
    sc.columns = *chain;
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    const double top = chain->back().z1;
    const double k = 1 / plan::chain_compliance(chains[0], top, sc, st, s);
    EXPECT_GE(k, s.min_stiffness) << "base at (" << chain->front().x0 << ", " << chain->front().y0 << ")";
    EXPECT_LE(std::hypot(chain->back().x1 - 50, chain->back().y1 - 50), 3.0 + 1e-9);
}

// A loop rests on the one below while it shifts by at most the reach over
// the gap between them. On layers of uneven height (KISSlicer slices each
// object on a Z grid of its own: here layers 0.09 and 0.11 mm apart in
// turn) a branch leaning to its trunk stepped by the lower layer's own
// height: 0.306 mm over a gap of 0.09, whose reach is 0.283, and
// kisslicer206_multiobject's branch left 0.14 mm^2 of its loops unheld.
TEST(PlanPillars, ABranchLeansByTheGapToTheLoopAboveOnUnevenLayers) {
    const Settings s = without_standing();
    std::vector<double> zs;
    for (int k = 1; k <= 60; ++k) zs.insert(zs.end(), {0.2 * k, 0.2 * k + 0.09});
    const layers::LayerStack st = test::stack_at(
        zs, [](int, layers::Layer& l) { test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter); }, {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    const TrunkAt50 t(st, obs, s);
    ASSERT_TRUE(t.trunk);
    const auto branch = plan::drop_pillar(51.5, 50, 80, plan::Top::Contact, st, obs, s, &t.trunks);
    ASSERT_TRUE(branch);
    ASSERT_EQ(branch->front().base, plan::Base::Column);
    auto centre = [&](double z) {
        for (const plan::Column& c : *branch)
            if (z > c.z0 + 1e-6 && z <= c.z1 + 1e-6) {
                double x, y;
                plan::column_centre_at(c, z, x, y);
                return std::pair{x, y};
            }
        ADD_FAILURE() << "no piece at z " << z;
        return std::pair{0.0, 0.0};
    };
    int leaning = 0;
    for (std::size_t l = 1; l + 1 < st.layers.size(); ++l) {
        const double z = st.layers[l].z, z_up = st.layers[l + 1].z;
        if (z <= branch->front().z0 + 1e-6 || z_up > branch->back().z1 + 1e-6) continue;
        const auto [x, y] = centre(z);
        const auto [xu, yu] = centre(z_up);
        const double shift = std::hypot(xu - x, yu - y);
        leaning += shift > 1e-9;
        EXPECT_LE(shift, plan::loop_shift_limit(z_up - z, s) + 1e-9) << "z " << z << " to " << z_up;
    }
    EXPECT_GT(leaning, 2);  // it leans on several layers
}

// A skirt or brim line is not the model: support keeps plan::kSkirtGap
// from it, not the 0.5 mm gap, where a column grows wider (room_clear). The
// hollow box's skirt runs along x = 95 on the first layer, its bead's edge
// 1.275 mm from x = 96.5 (the box's wall 3.275 mm off): a disc of 1.6 mm
// meets it with the whole gap counted (disc_clear, how a way down is
// found), misses it with 0.4 of the gap given back (1.2 < 1.275), and one
// of 1.8 meets it either way. Beside the model the whole gap counts, and a
// layer with no skirt answers as disc_clear does.
TEST(Obstacles, ASkirtLineKeepsOnlyItsOwnGapFromAWideningColumn) {
    Settings s;
    const auto st = hollow_box(gcode::Role::Perimeter);
    const plan::Obstacles obs(st, s);
    EXPECT_FALSE(obs.disc_clear(0, 96.5, 110, 1.6));
    EXPECT_TRUE(obs.room_clear(0, 96.5, 110, 1.6));
    EXPECT_FALSE(obs.room_clear(0, 96.5, 110, 1.8));
    // 1.5 mm from the box's wall (its edge 1.275 off): the whole gap.
    EXPECT_FALSE(obs.disc_clear(0, 98.5, 110, 1.6));
    EXPECT_FALSE(obs.room_clear(0, 98.5, 110, 1.6));
    for (double r : {1.0, 1.6, 1.8, 2.6}) EXPECT_EQ(obs.room_clear(1, 96.5, 110, r), obs.disc_clear(1, 96.5, 110, r)) << r;
}

// A column whose bottom loops pass a skirt line 2 mm off its centre (the
// line's bead edge 1.775 off) widens there as far as kSkirtGap and half a
// cell from it allow, no longer stopping 0.5 mm short: a plain 2 mm column
// 40 mm tall on 0.2 mm layers wants r(z) = 1 + t (40 - z) with t about
// 0.055 (the tube test in braces_test), over 3 mm at the bed; beside the
// skirt it gets 1.775 - 0.1 = 1.675 at most (and half a cell: the line's
// raster), where with the whole gap it got 1.275 at most.
TEST(PlanPillars, AColumnWidensBesideASkirtLineToItsOwnGap) {
    Settings s;
    const layers::LayerStack st = test::stack_of(
        205,
        [](int i, layers::Layer& l) {
            test::bead(l, 0, 0, 0.5, 0, gcode::Role::Perimeter);
            if (i == 0) test::bead(l, 52, 30, 52, 70, gcode::Role::Skirt);
        },
        {-5, -5, 80, 80});
    const plan::Obstacles obs(st, s);
    std::vector<plan::Column> chain{bar_column_at_50(40)};
    ASSERT_TRUE(plan::widen_column(chain, st, obs, s));
    auto radius_at = [&](double z) {
        for (const plan::Column& c : chain)
            if (z > c.z0 + 1e-6 && z <= c.z1 + 1e-6) return plan::column_radius_at(c, z, s);
        ADD_FAILURE() << "no piece at z " << z;
        return 0.0;
    };
    // (The raster of the line falls up to half a cell short of its edge.)
    const double r0 = radius_at(st.layers[0].z);
    EXPECT_GT(r0, 1.5);
    EXPECT_LE(r0, 1.775 - plan::kSkirtGap + s.resolution / 2);
    // The next layer has no skirt: as wide as a loop may step out on it.
    const double r1 = radius_at(st.layers[1].z);
    EXPECT_GT(r1, r0);
    EXPECT_LE(r1 - r0, plan::loop_shift_limit(0.2, s) + 1e-9);
}

// A tip in a slot too narrow for the normal column (walls 2.8 mm apart from
// z 8 to 12.4, their rasters 1.25 mm from its centre: a 1 mm column needs
// 1 + 0.5 + 0.05, and with its longest neck, 6 mm, it is 0.87 mm at z 8)
// gets the thin one (0.6 mm); below the slot one wall goes on to the bed.
// The normal column would need no taper: 12.4 mm of a 2 mm ring stands
// 3 x 2303.22 / 12.4^3 = 3.63 N/mm. The thin one, 3 x 260.93 / 12.4^3 =
// 0.41 N/mm plain, needs one of its own: found with it, its way down steps
// away from the wall below the slot, where the room is, and it stands the
// rule. It used to get the normal column's none: a plain way down along
// the wall, widened only in place there, 0.6 to 0.7 mm (an elephant's
// column between its legs, 1.2 N/mm).
TEST(PlanPillars, AThinColumnGetsATaperOfItsOwn) {
    Settings s;
    constexpr int kTop = 61;  // z 12.4
    const layers::LayerStack st = stack_with(kTop + 3, [](int i, layers::Layer& l) {
        if (i <= kTop) test::bead(l, 48.6, 40, 48.6, 60, gcode::Role::Perimeter);
        if (i >= 39 && i <= kTop) test::bead(l, 51.4, 40, 51.4, 60, gcode::Role::Perimeter);
        if (i == kTop + 1) test::bead(l, 49.3, 50, 50.7, 50);  // the overhang: over the slot only
    });
    const plan::Obstacles obs(st, s);
    EXPECT_NEAR(plan::taper_for(1.0, 12.4, plan::target_stiffness(s), 0, s.support_width, s.modulus), 0, 1e-12);
    const auto chain = plan::drop_pillar(50, 50, kTop + 1, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain.has_value());
    ASSERT_FALSE(chain->empty());
    EXPECT_NEAR(chain->front().radius, 0.6, 1e-9);
    EXPECT_GT(chain->front().taper, 0);
    EXPECT_EQ(chain->front().base, plan::Base::Bed);
    EXPECT_GE(stands_at(*chain, 12.4, st, s), s.min_stiffness);
}

// A column coming down right over the outer edge of a brim (Cura's: lines
// side by side round the model, here to x 50.2 on the first layer), in a
// slot between two thick walls (inner edges at x 48.3 and 51.7, z 0.6 to
// 12.4: a 2 mm column's centre within 0.2 mm of x 50; no tip beside them
// within reach) that keeps it from stepping off the brim before: at the
// bed it has no room and no brim
// under all of its bottom loop. That loop moves onto the brim, as far as a
// loop may shift on the one above (0.8 (0.2 tan 55 + 0.225) = 0.4085 mm):
// at x 49.59 its centre line (radius 0.775) reaches 50.37, within the rest
// reach (0.8 x 0.2 tan 55 = 0.229) of the brim's edge. So the normal 2 mm
// column stands there (12.4 mm: 2.05 N/mm with no taper), where the old
// descent left only a thin one, 1.2 mm, 1.19 N/mm (cura531_benchy at
// --min-overhang-area 0: the thinnest, 0.18 N/mm).
TEST(PlanPillars, AColumnAtABrimsEdgeStepsOntoTheBrim) {
    Settings s;
    constexpr int kTop = 61;  // z 12.4
    const layers::LayerStack st = stack_with(kTop + 3, [](int i, layers::Layer& l) {
        if (i == 0)
            for (double y = 40; y <= 60; y += 0.45) test::bead(l, 30, y, 49.975, y, gcode::Role::Skirt);
        for (int k = 0; i >= 2 && i <= kTop && k < 8; ++k) {  // 3.6 mm thick each
            test::bead(l, 48.075 - 0.45 * k, 40, 48.075 - 0.45 * k, 60, gcode::Role::Perimeter);
            test::bead(l, 51.925 + 0.45 * k, 40, 51.925 + 0.45 * k, 60, gcode::Role::Perimeter);
        }
        if (i == kTop + 1) test::bead(l, 49.3, 50, 50.7, 50);  // the overhang
    });
    const plan::Obstacles obs(st, s);
    const auto chain = plan::drop_pillar(50, 50, kTop + 1, plan::Top::Contact, st, obs, s);
    ASSERT_TRUE(chain.has_value());
    ASSERT_FALSE(chain->empty());
    EXPECT_NEAR(chain->front().radius, 1.0, 1e-9);
    EXPECT_EQ(chain->front().base, plan::Base::Model);
    EXPECT_NEAR(chain->front().z0, 0.2, 1e-6);
    EXPECT_LT(chain->front().x0, 50 - 0.3);  // moved in over the brim
    EXPECT_GE(stands_at(*chain, 12.4, st, s), s.min_stiffness);
}

// A 2 mm column 40 mm tall (a tip's, on the bed) between two walls of
// model from z 8 to 20, 2.6 mm either side of its centre: their beads'
// edges 2.375 mm off, so its loops there reach 2.375 - 0.5 (the gap) and
// half a cell at most, 1.9 mm. The Standing rule's taper for a straight
// column, 0.0553 (2.5 N/mm, taper_for), wants 1.55 to 2.22 mm there:
// capped, by the ring model (the capped part taken at 1.9 mm throughout,
// centre line 1.675 mm: (32^3 - 20^3) / 3 / (3500 pi 0.45 1.675^3) =
// 8256 / 23252 = 0.3551 mm/N; the rest at the taper, integrated: 0.1504
// above the walls, 0.0990 below), it stands 1 / 0.6045 = 1.654 N/mm,
// short of the rule. Widened as far as the room allows at more
// taper where the walls leave room, above and below them, it stands.
TEST(PlanPillars, AColumnCappedBesideTheModelTakesMoreTaperWhereThereIsRoom) {
    Settings s;
    const layers::LayerStack st = stack_with(203, [](int i, layers::Layer& l) {
        if (i >= 40 && i < 100) {  // z 8.2 to 20
            test::bead(l, 47.4, 40, 47.4, 60, gcode::Role::Perimeter);
            test::bead(l, 52.6, 40, 52.6, 60, gcode::Role::Perimeter);
        }
    });
    const plan::Obstacles obs(st, s);
    const double w = s.support_width, e = s.modulus;
    const double full = plan::taper_for(1.0, 40, plan::target_stiffness(s), 0, w, e);
    EXPECT_NEAR(full, 0.0553, 0.0001);
    // The straight rule's taper, capped: short (the estimate above).
    const double capped = plan::ring_compliance(1.0, full, 40, 20, 40, w, e) +
                          plan::ring_compliance(1.9, 0, 40, 8, 20, w, e) +
                          plan::ring_compliance(1.0, full, 40, 0, 8, w, e);
    EXPECT_NEAR(plan::ring_compliance(1.9, 0, 40, 8, 20, w, e), 0.3551, 0.0001);
    EXPECT_NEAR(1 / capped, 1.654, 0.001);
    std::vector<plan::Column> chain{bar_column_at_50(40)};
    ASSERT_TRUE(plan::widen_column(chain, st, obs, s));
    plan::Scaffold sc;
    sc.columns = chain;
    const auto chains = plan::pillar_chains(sc);
    ASSERT_EQ(chains.size(), 1u);
    EXPECT_GE(1 / plan::chain_compliance(chains[0], 40, sc, st, s), s.min_stiffness);
    // One taper, more than the straight rule's, and the least that stands
    // (by half a percent of the rule, the search's steps).
    const double taper = chain.front().taper;
    EXPECT_GT(taper, full + 0.005);
    for (const plan::Column& c : chain) EXPECT_EQ(c.taper, taper);
    EXPECT_LT(1 / plan::chain_compliance(chains[0], 40, sc, st, s), plan::kGiveMargin * s.min_stiffness * 1.05);
    double below = 0;
    for (int l = 0; l < 200; ++l) {
        const double z = st.layers[l].z;
        const auto piece = std::find_if(chain.begin(), chain.end(), [&](const plan::Column& c) {
            return z > c.z0 + 1e-6 && z <= c.z1 + 1e-6;
        });
        ASSERT_NE(piece, chain.end()) << "z " << z;
        const double r = plan::column_radius_at(*piece, z, s);
        EXPECT_TRUE(obs.disc_clear(l, 50, 50, r + s.xy_gap)) << "z " << z;
        if (z > 8.1 && z < 20.1) {
            EXPECT_LE(r, 2.375 - s.xy_gap + s.resolution) << "z " << z;
        }
        if (z > 24) {  // the taper where there is room
            EXPECT_NEAR(r, 1.0 + taper * (40 - z), 1e-9) << "z " << z;
        }
        if (l > 0) {
            EXPECT_LE(std::abs(r - below), plan::loop_shift_limit(0.2, s) + 1e-9) << "z " << z;
        }
        below = r;
    }
}
