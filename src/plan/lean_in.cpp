#include "plan/lean_in.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "plan/braces.hpp"
#include "plan/stiffness.hpp"

namespace scaffold::plan {

namespace {

// The give of a lean-in's columns (its pillar and the leaning one, bottom
// up) at the tip, from the pillar's base, as METHOD sums it layer by layer.
double lean_in_compliance(const std::vector<Column>& chain, const layers::LayerStack& stack, const Settings& s) {
    Scaffold sc;
    sc.columns = chain;
    PillarChain whole;
    for (std::size_t i = 0; i < chain.size(); ++i) whole.pieces.push_back(static_cast<int>(i));
    whole.base = chain.front().z0;
    whole.top = whole.hold = chain.back().z1;
    return chain_compliance(whole, whole.top, sc, stack, s);
}

}  // namespace

std::optional<std::vector<Column>> lean_in(double x, double y, int overhang_layer, const layers::LayerStack& stack,
                                           const Obstacles& obs, const Settings& s, const Trunks* trunks) {
    const int top_layer = tip_layer(stack, overhang_layer, s);
    if (top_layer < 0) return std::nullopt;
    // The layers below the tip, top first.
    std::vector<int> down;
    for (int l = top_layer; l >= 0 && static_cast<int>(down.size()) < 400; l = stack.layers[l].below)
        down.push_back(l);
    Column lean;
    lean.z1 = stack.layers[top_layer].z;
    lean.contact_z = lean.z1;
    lean.radius = s.tip_radius;  // thin all the way: it stands on the pillar's tapered top
    lean.top = Top::Contact;
    lean.base = Base::Column;
    int pillars_tried = 0;
    // METHOD's Standing rule: the first lean-in found that stands is taken;
    // one short of it (the shuttle's: a pillar walking 13 mm round the hull,
    // then leaning 8 mm in over 4 mm, 1.45 N/mm) looks on, a few more at
    // most, and else the stiffest found is taken.
    std::optional<std::vector<Column>> weak;
    double weak_k = -1;
    int weak_tries = 0;
    const bool seek_standing = target_stiffness(s) > 0;
    static constexpr std::array<double, 9> kRings{1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.5, kLeanInReach};
    // The tip at the point or, where its own contact has no room, beside it
    // under the overhanging layer's material (METHOD's rule (c)).
    static constexpr std::array<double, 5> kTipRings{0.0, 0.25, 0.5, 0.75, 1.0};
    for (double dt : kTipRings)
        for (int tdir = 0; tdir < (dt == 0 ? 1 : 8); ++tdir) {
            const double tx = x + dt * std::cos(tdir * std::numbers::pi / 4), ty = y + dt * std::sin(tdir * std::numbers::pi / 4);
            if (dt > 0 && obs.disc_clear(overhang_layer, tx, ty, s.tip_radius + s.resolution)) continue;
            lean.x1 = tx;
            lean.y1 = ty;
            if (!obs.disc_clear(top_layer, tx, ty, column_radius_at(lean, lean.z1, s) + clearance_at(lean, lean.z1, s)))
                continue;
            for (double d : kRings)
                for (int dir = 0; dir < 16; ++dir) {
                    const double a = dir * std::numbers::pi / 8, px = tx + d * std::cos(a), py = ty + d * std::sin(a);
                    // Lean over as many layers as a loop needs to shift no
                    // more than it may on the one below; the first loop
                    // stands on the pillar.
                    std::size_t n = 1;  // layers of the leaning column: down[0..n-1]
                    double step = 1e9;
                    do {
                        step = std::min(step, loop_shift_limit(stack.layers[down[n - 1]].height, s));
                        ++n;
                    } while (n < down.size() && d / static_cast<double>(n - 1) > step);
                    if (n >= down.size() || d / static_cast<double>(n - 1) > step) continue;
                    Column c = lean;
                    c.x0 = px;
                    c.y0 = py;
                    c.z0 = stack.layers[down[n]].z;
                    c.lean_from = stack.layers[down[n - 1]].z;
                    // The leaning column clear of the model over its layers.
                    auto clear_path = [&](const Column& lc) {
                        for (std::size_t k = 1; k < n; ++k) {
                            const double z = stack.layers[down[k]].z;
                            double cx, cy;
                            column_centre_at(lc, z, cx, cy);
                            if (!obs.disc_clear(down[k], cx, cy, column_radius_at(lc, z, s) + clearance_at(lc, z, s)))
                                return false;
                        }
                        return true;
                    };
                    // A pillar under it up to its first loop, sized for the
                    // leaning column's top, with its give.
                    auto build = [&](Column lc) -> std::optional<std::vector<Column>> {
                        const double give = target_stiffness(s) > 0 ? ring_compliance(lc.radius, 0, lc.z1, lc.z0, lc.z1,
                                                                                       s.support_width, s.modulus)
                                                                     : 0.0;
                        auto chain = drop_pillar(px, py, down[n - 1], Top::Bridge, stack, obs, s, trunks, TipPlaces::Any,
                                                 true, lc.z1, give, true);
                        if (!chain) return std::nullopt;
                        if (s.buildplate_only && (chain->empty() || chain->front().base != Base::Bed)) return std::nullopt;
                        if (chain->empty()) lc.base = Base::Model;  // the model's top holds it
                        chain->push_back(lc);
                        return chain;
                    };
                    if (!clear_path(c)) continue;
                    // A bounded number of pillars per point (each walks down
                    // the stack), so a point nothing reaches costs little.
                    if (++pillars_tried > kLeanInPillars) return weak;
                    auto chain = build(c);
                    if (!chain) continue;
                    if (!seek_standing) return chain;
                    double k = 1 / lean_in_compliance(*chain, stack, s);
                    if (k >= kGiveMargin * s.min_stiffness) return chain;
                    // Short of the rule: the leaning column as wide as a
                    // pillar where it clears the model (its tip still necks
                    // down): a 0.5 mm ring leaning 8 mm over 4.2 gives
                    // 0.24 mm/N, a 1 mm one about 22 times less.
                    Column wide = c;
                    wide.radius = std::max(c.radius, s.pillar_radius);
                    if (wide.radius > c.radius && clear_path(wide))
                        if (auto wider = build(wide)) {
                            const double kw = 1 / lean_in_compliance(*wider, stack, s);
                            if (kw > k) {
                                k = kw;
                                chain = std::move(wider);
                            }
                            if (k >= kGiveMargin * s.min_stiffness) return chain;
                        }
                    if (k > weak_k) {
                        weak_k = k;
                        weak = std::move(chain);
                    }
                    if (++weak_tries > kWeakLeanTries) return weak;
                }
        }
    return weak;
}

std::optional<LeanInAnswers::Chain> LeanInAnswers::find(double x, double y, int layer) const {
    const std::lock_guard lock(mutex_);
    const auto it = map_.find({std::llround(x * 1000), std::llround(y * 1000), layer});
    return it == map_.end() ? std::nullopt : std::optional<Chain>(it->second);
}

void LeanInAnswers::insert(double x, double y, int layer, const Chain& chain) {
    const std::lock_guard lock(mutex_);
    map_.emplace(Key{std::llround(x * 1000), std::llround(y * 1000), layer}, chain);
}

std::optional<std::vector<Column>> support_point(double x, double y, int overhang_layer,
                                                 const layers::LayerStack& stack, const Obstacles& obs,
                                                 const Settings& s, const Trunks* trunks, bool beside,
                                                 LeanInAnswers* known) {
    auto chain = drop_pillar(x, y, overhang_layer, Top::Contact, stack, obs, s, trunks, TipPlaces::UnderSheet);
    // METHOD's Standing rule: a pillar capped by the model beside it all the
    // way down may stand short of it where a lean-in from a pillar that
    // stands in the open does not (the shuttle: 0.41 N/mm against 2.07).
    // Compared from the bed or the model up, on pillars of their own (a
    // column on another is not judged here).
    if (chain && target_stiffness(s) > 0 && chain->front().base != Base::Column) {
        const double k = 1 / lean_in_compliance(*chain, stack, s);
        if (k < kGiveMargin * s.min_stiffness) {
            std::optional<LeanInAnswers::Chain> lean = known ? known->find(x, y, overhang_layer) : std::nullopt;
            if (!lean) {
                lean = lean_in(x, y, overhang_layer, stack, obs, s, nullptr);
                if (known) known->insert(x, y, overhang_layer, *lean);
            }
            if (*lean && 1 / lean_in_compliance(**lean, stack, s) > k) return **lean;
        }
    }
    if (chain) return chain;
    if (auto lean = lean_in(x, y, overhang_layer, stack, obs, s, trunks)) return lean;
    if (!beside) return std::nullopt;
    return drop_pillar(x, y, overhang_layer, Top::Contact, stack, obs, s, trunks, TipPlaces::Beside);
}

void add_pillars(Scaffold& scaffold, const overhang::SupportPoints& points, const std::vector<int>& which,
                 const layers::LayerStack& stack, const Obstacles& obs, const Settings& s, double steer, bool beside) {
    Trunks trunks(stack, steer);
    trunks.add(scaffold.columns, stack, s);
    for (int i : which) {
        const overhang::SupportPoint& p = points.points[i];
        auto chain = support_point(p.x, p.y, p.layer, stack, obs, s, &trunks, beside);
        if (!chain) {
            scaffold.dropped_points.push_back(i);
            continue;
        }
        trunks.add(*chain, stack, s);
        for (Column& c : *chain) {
            c.point = i;
            scaffold.columns.push_back(c);
        }
    }
    std::sort(scaffold.dropped_points.begin(), scaffold.dropped_points.end());
}

}  // namespace scaffold::plan
