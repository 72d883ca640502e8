#include "plan/planner.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <utility>

#include "layers/layer_stack.hpp"
#include "plan/cavities.hpp"
#include "plan/lean_in.hpp"
#include "plan/pillars.hpp"
#include "plan/stiffness.hpp"

namespace scaffold::plan {

namespace {

// A slanted column from the bar's top up to (tx, ty) under the active
// point; nullopt when it leans more than printable on some layer or comes
// within the gap of the model.
std::optional<Column> connector_to(const Candidate& b, const Active& a, double tx, double ty, const ModelView& m,
                                   const Settings& s) {
    double dx = b.x1 - b.x0, dy = b.y1 - b.y0, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((tx - b.x0) * dx + (ty - b.y0) * dy) / len2, 0.0, 1.0) : 0;
    Column c;
    c.x0 = b.x0 + dx * t;
    c.y0 = b.y0 + dy * t;
    c.z0 = b.z + kBarThickness;
    c.x1 = tx;
    c.y1 = ty;
    c.z1 = a.z;
    c.radius = kConnectorRadius;
    c.base = Base::Bridge;
    c.top = a.point >= 0 ? Top::Contact : Top::Bridge;
    c.contact_z = a.point >= 0 ? c.z1 : 0;
    c.point = a.point;
    if (c.z1 <= c.z0 + 1e-6) return std::nullopt;
    std::vector<double> layers = m.tops_between(c.z0, c.z1, s.layer_height);
    if (layers.empty()) return std::nullopt;
    const double dist = std::hypot(c.x1 - c.x0, c.y1 - c.y0);
    // The first loop stands on the bar, centred on it; the lean starts there.
    if (dist > 0) {
        if (layers.size() < 2) return std::nullopt;
        c.lean_from = layers.front();
    }
    const double lean_z0 = std::max(c.z0, c.lean_from);
    double prev = lean_z0;
    for (double z : layers) {
        if (z > lean_z0 + 1e-9) {
            double shift = dist * (z - prev) / (c.z1 - lean_z0);
            if (shift > max_lean_per_layer(z - prev, s) + 1e-6) return std::nullopt;
            prev = z;
        }
        if (!m.disc_clear) continue;
        double x, y;
        column_centre_at(c, z, x, y);
        if (!m.disc_clear(z, x, y, column_radius_at(c, z, s) + clearance_at(c, z, s))) return std::nullopt;
    }
    return c;
}

// The connector to the point itself or, for a support point whose straight
// connector is blocked, to a tip up to 1.5 mm away (the tip still holds the
// point: its radius is 3.5 mm). A bridge end must be met exactly. METHOD's
// rule (c): a tip holds only the sheet resting on it, so a tip away from the
// point must still lie under the overhanging layer's material; where none
// does, the bridge does not carry the point (a pillar may still reach it).
std::optional<Column> connector(const Candidate& b, const Active& a, const ModelView& m, const Settings& s) {
    if (auto c = connector_to(b, a, a.x, a.y, m, s)) return c;
    if (a.point < 0 || !m.disc_clear) return std::nullopt;
    for (double d : {0.25, 0.5, 0.75, 1.0, 1.5})
        for (int k = 0; k < 8; ++k) {
            const double ang = k * std::numbers::pi / 4, x = a.x + d * std::cos(ang), y = a.y + d * std::sin(ang);
            if (m.touches_above && !m.touches_above(a.z, x, y, s.tip_radius + s.resolution)) continue;
            if (auto c = connector_to(b, a, x, y, m, s)) return c;
        }
    return std::nullopt;
}

}  // namespace

struct BridgePlan {
    std::vector<Bridge> bridges;
    std::vector<Column> connectors;
    std::vector<Active> remaining;  // to stand on pillars, in a fixed order
};

struct BridgeReplay::Log {
    struct Snap {
        std::size_t offers = 0;  // made before it
        std::unique_ptr<BridgeSearch> search;
        BridgePlan out;
        long rejects_left = 0;
    };
    std::vector<Snap> snaps;            // ascending by offers
    std::vector<Candidate> offered;     // what the search offered, in order
    std::vector<char> trapped;          // whether bar_trapped turned it down
    std::vector<Active> start;          // the points it was made for
    // Offers between two kept states: every one at first (a plan whose
    // search leaves forbidden bars out offers little more than the bars it
    // takes), doubling as the states thin out.
    std::size_t every = 1;
};

BridgeReplay::BridgeReplay() = default;
BridgeReplay::~BridgeReplay() = default;

namespace {

// States of a search kept at most: past this, every other one goes and
// the offers between two double (a plan made again makes at most that many
// offers again before it reaches where it first differs).
constexpr std::size_t kReplaySnaps = 64;

bool same_start(const std::vector<Active>& a, const std::vector<Active>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const Active& p, const Active& q) {
        return p.x == q.x && p.y == q.y && p.z == q.z && p.point == q.point && p.hold == q.hold && p.give == q.give;
    });
}

// The greedy loop (METHOD.md step 4): take the best bridge that can really
// be built, remove what it carries, add its two ends, repeat.
BridgePlan plan_bridges(const std::vector<Active>& start, const ModelView& m, const Settings& s, int threads = 0,
                        std::shared_ptr<ModelAnswers> answers = nullptr, BridgeReplay* replay = nullptr,
                        const std::vector<const ModelView*>& helpers = {}, const Forbidden& forbidden = {}) {
    BridgePlan out;
    std::unique_ptr<BridgeSearch> owned;
    // Bounded work where the model is in the way everywhere.
    long rejects_left = 20000 + 400 * static_cast<long>(start.size());
    BridgeReplay::Log* log = replay ? replay->log.get() : nullptr;
    if (log && !log->snaps.empty() && same_start(log->start, start)) {
        // The first offer this plan turns down as trapped where the last did
        // not: every step before it is the same.
        std::size_t first = 0;
        while (first < log->offered.size()) {
            const Candidate& c = log->offered[first];
            if (!log->trapped[first] && m.bar_trapped && m.bar_trapped(c.z, c.x0, c.y0, c.x1, c.y1)) break;
            ++first;
        }
        while (log->snaps.size() > 1 && log->snaps.back().offers > first) log->snaps.pop_back();
        const BridgeReplay::Log::Snap& from = log->snaps.back();
        owned = from.search->clone(m, helpers);
        // Its seeds were searched without the bars forbidden since (the
        // search leaves them out itself): those that may offer one, again.
        for (const Bridge& f : forbidden.bars) owned->stale_near(f.x0, f.y0, f.x1, f.y1);
        for (const Xyz& f : forbidden.places) owned->stale_near(f.x, f.y, f.x, f.y);  // kPlaceNear within its 2 mm
        out = from.out;
        rejects_left = from.rejects_left;
        log->offered.resize(from.offers);
        log->trapped.resize(from.offers);
        replay->offers_replayed += static_cast<long long>(from.offers);
    } else {
        owned = std::make_unique<BridgeSearch>(m, s, threads, std::move(answers), helpers);
        for (const Active& a : start) owned->add(a);
        if (replay) {
            replay->log = std::make_unique<BridgeReplay::Log>();
            log = replay->log.get();
            log->start = start;
        }
    }
    BridgeSearch& search = *owned;
    for (;;) {
        if (log && log->offered.size() % log->every == 0 &&
            (log->snaps.empty() || log->snaps.back().offers < log->offered.size())) {
            search.refresh();
            log->snaps.push_back({log->offered.size(), search.clone(m, helpers), out, rejects_left});
            if (log->snaps.size() > kReplaySnaps) {
                std::vector<BridgeReplay::Log::Snap> kept;
                for (std::size_t i = 0; i < log->snaps.size(); i += 2) kept.push_back(std::move(log->snaps[i]));
                log->snaps = std::move(kept);
                log->every *= 2;
            }
        }
        auto c = search.best();
        if (!c) break;
        const double len = std::hypot(c->x1 - c->x0, c->y1 - c->y0);
        std::vector<Column> connectors;
        std::vector<int> carried;
        double l_max = 0;
        double hold = 0, give = 0;  // over the connectors: for the pillars under the ends
        // Ends first (cached), then connectors until too many have failed
        // for the gain to stay positive.
        const bool trapped = m.bar_trapped && m.bar_trapped(c->z, c->x0, c->y0, c->x1, c->y1);
        if (log) {
            log->offered.push_back(*c);
            log->trapped.push_back(trapped);
        }
        bool ok = !trapped && search.end_stands(c->x0, c->y0, c->z) && search.end_stands(c->x1, c->y1, c->z);
        for (std::size_t i = 0; ok && i < c->carried.size(); ++i) {
            const int id = c->carried[i];
            const Active& a = search.active(id);
            // METHOD's Standing rule: a connector is a thin column on a bar;
            // with what stands on it, it may give at most half of what the
            // whole may (the pillar under the bar takes the rest). Its give
            // depends on the heights alone (a kConnectorRadius stick from the
            // bar's top up to a.z, however it leans), so it is asked before
            // the connector is searched for (a plate's bunny copy: 3056 bars
            // offered whose connectors were all too tall).
            const double top = std::max(a.z, a.hold);
            double give_i = 0;
            bool stiff = true;
            if (connector_allowance(s) > 0 && a.z > c->z + kBarThickness) {
                give_i = a.give + connector_compliance(a, c->z, len, s);
                stiff = give_i <= connector_allowance(s);
            }
            std::optional<Column> col;
            if (stiff) col = connector(*c, a, m, s);
            if (col) {
                hold = std::max(hold, top);
                give = std::max(give, give_i);
                connectors.push_back(*col);
                carried.push_back(id);
                l_max = std::max(l_max, std::hypot(col->x1 - col->x0, col->y1 - col->y0) + col->z1 - c->z);
            } else {
                search.no_connector(id, *c);
            }
            int most = static_cast<int>(carried.size() + c->carried.size() - i - 1);
            ok = bridge_gain(most, c->z, len) > 0;
        }
        const int k = static_cast<int>(carried.size());
        if (!ok) {
            search.reject(*c);
            if (--rejects_left <= 0) break;
            continue;
        }
        Bridge br{c->x0, c->y0, c->x1, c->y1, c->z, {}, bridge_gain(k, c->z, len), 0};
        br.score = bridge_score(br.gain, k, l_max);
        for (int id : carried)
            if (search.active(id).point >= 0) br.points.push_back(search.active(id).point);
        out.bridges.push_back(std::move(br));
        out.connectors.insert(out.connectors.end(), connectors.begin(), connectors.end());
        for (int id : carried) search.remove(id);
        search.add({c->x0, c->y0, c->z, -1, hold, give});
        search.add({c->x1, c->y1, c->z, -1, hold, give});
    }
    for (int id = 0; id < search.size(); ++id)
        if (search.alive(id)) out.remaining.push_back(search.active(id));
    return out;
}

// A vertical pillar from the bed or the model's top up to the active point.
std::optional<Column> vertical_pillar(const Active& a, const ModelView& m, const Settings& s) {
    Column c;
    c.x0 = c.x1 = a.x;
    c.y0 = c.y1 = a.y;
    c.z1 = a.z;
    c.z0 = m.model_top_below ? m.model_top_below(a.z, a.x, a.y, s.pillar_radius) : 0;
    c.base = c.z0 > 0 ? Base::Model : Base::Bed;
    c.top = a.point >= 0 ? Top::Contact : Top::Bridge;
    c.point = a.point;
    c.contact_z = c.z1;  // tapered top, under a bridge end too (as drop_pillar)
    c.radius = std::max(s.pillar_radius, c.z1 / (2 * s.slenderness));
    if (c.base == Base::Model && s.buildplate_only) return std::nullopt;
    if (c.base == Base::Bed) {
        if (c.z1 - c.z0 > kFootMinHeight) c.foot_radius = s.foot_radius;
        c.raft_size = s.raft_size;
    }
    return c;
}

// Layer tops and the layer indices at each, from the obstacle rasters.
struct LayerIndex {
    std::vector<std::pair<double, int>> by_z;  // (top z, layer), ascending
    std::vector<int> at(double z) const {
        std::vector<int> out;
        auto it = std::lower_bound(by_z.begin(), by_z.end(), std::make_pair(z - 1e-6, -1));
        for (; it != by_z.end() && it->first <= z + 1e-6; ++it) out.push_back(it->second);
        return out;
    }
    int above(double z) const {  // a layer whose top is the first one above z, or -1
        auto it = std::lower_bound(by_z.begin(), by_z.end(), std::make_pair(z + 1e-6, -1));
        return it == by_z.end() ? -1 : it->second;
    }
};

// Where the support of support point i reaches up to: the top of the layer
// under it, less --top-gap-layers.
double point_top(const overhang::SupportPoint& p, const ModelView& m, const Settings& s) {
    double z = m.snap_down(p.z);
    if (z < 0) z = p.z;
    for (int k = 0; k < s.top_gap_layers; ++k) z = m.snap_down(z - 1e-3);
    return z;
}

}  // namespace

ModelView model_view(const Obstacles& obs) {
    auto index = std::make_shared<LayerIndex>();
    for (int l = 0; l < obs.layer_count(); ++l) index->by_z.emplace_back(obs.layer_z(l), l);
    std::stable_sort(index->by_z.begin(), index->by_z.end());
    ModelView v;
    for (const auto& [z, l] : index->by_z)
        if (z > 1e-6 && (v.layer_tops.empty() || z > v.layer_tops.back() + 1e-6)) v.layer_tops.push_back(z);
    v.segment_clear = [&obs, index](double z, double x0, double y0, double x1, double y1, double r) {
        const std::vector<int> layers = index->at(z);
        // Most bars the search asks about are blocked: the grown raster
        // (model + obs.inflate) says so at a few cells' cost.
        if (r >= obs.inflate)
            for (int l : layers)
                if (!obs.line_clear(l, x0, y0, x1, y1)) return false;
        for (int l : layers)
            if (!obs.segment_clear(l, x0, y0, x1, y1, r)) return false;
        return true;
    };
    v.disc_clear = [&obs, index](double z, double x, double y, double r) {
        for (int l : index->at(z))
            if (!obs.disc_clear(l, x, y, r)) return false;
        return true;
    };
    v.touches_above = [&obs, index](double z, double x, double y, double r) {
        const int l = index->above(z);
        return l >= 0 && !obs.disc_clear(l, x, y, r);
    };
    v.model_top_below = [&obs, index](double z, double x, double y, double r) {
        // model_below looks under a layer: ask from the layer above the top.
        int above = index->above(z);
        if (above >= 0) {
            int l = obs.model_below(above, x, y, r);
            return l < 0 ? 0.0 : obs.layer_z(l);
        }
        for (auto it = index->by_z.rbegin(); it != index->by_z.rend(); ++it)
            if (it->first <= z + 1e-6 && !obs.disc_clear(it->second, x, y, r)) return it->first;
        return 0.0;
    };
    return v;
}

std::optional<Candidate> best_bridge(const std::vector<Active>& active, const ModelView& model, const Settings& s) {
    BridgeSearch search(model, s);
    for (const Active& a : active) search.add(a);
    return search.best();
}

Scaffold plan_scaffold(const overhang::SupportPoints& points, const Obstacles& obstacles, const Settings& s) {
    return plan_scaffold(points, model_view(obstacles), s);
}

Scaffold plan_scaffold(const overhang::SupportPoints& points, const ModelView& model, const Settings& s, int threads) {
    ModelView m = model;
    if (s.buildplate_only && !m.end_stands && m.model_top_below)
        m.end_stands = [&model, &s](double x, double y, double z) {
            return model.model_top_below(z, x, y, s.pillar_radius) <= 0;
        };
    std::vector<Active> start;
    for (int i : canonical_order(points)) {
        const auto& p = points.points[i];
        start.push_back({p.x, p.y, point_top(p, m, s), i});
    }
    BridgePlan plan = plan_bridges(start, m, s, threads);
    Scaffold out;
    out.bridges = std::move(plan.bridges);
    out.columns = std::move(plan.connectors);
    for (const Active& a : plan.remaining) {
        auto c = vertical_pillar(a, m, s);
        if (c && c->z1 - c->z0 > 1e-6)
            out.columns.push_back(*c);
        else if (a.point >= 0)
            out.dropped_points.push_back(a.point);
    }
    std::sort(out.dropped_points.begin(), out.dropped_points.end());
    return out;
}

namespace {

// hypot(dx, dy) < r, the squares compared where they settle it (the search
// asks this of every candidate near a forbidden bar): the same answer.
bool closer_than(double dx, double dy, double r) {
    const double d2 = dx * dx + dy * dy, r2 = r * r;
    if (d2 < r2 * (1 - 1e-9)) return true;
    if (d2 > r2 * (1 + 1e-9)) return false;
    return std::hypot(dx, dy) < r;
}

// Whether bar b runs along f's line: parallel within kForbiddenAngleDeg, its
// ends within kForbiddenBeside of that line, over at least half the
// shorter's length. The cheapest test first (the four must all hold).
bool along(const Bridge& f, const Bridge& b) {
    const double fl = std::hypot(f.x1 - f.x0, f.y1 - f.y0);
    if (fl < 1e-9) return false;
    const double ux = (f.x1 - f.x0) / fl, uy = (f.y1 - f.y0) / fl;
    auto beside = [&](double x, double y) { return std::abs(-uy * (x - f.x0) + ux * (y - f.y0)); };
    if (beside(b.x0, b.y0) > kForbiddenBeside || beside(b.x1, b.y1) > kForbiddenBeside) return false;
    const double bl = std::hypot(b.x1 - b.x0, b.y1 - b.y0);
    if (bl < 1e-9) return false;
    const double cos = std::abs(ux * (b.x1 - b.x0) + uy * (b.y1 - b.y0)) / bl;
    if (cos < std::cos(kForbiddenAngleDeg * std::numbers::pi / 180)) return false;
    const double t0 = ux * (b.x0 - f.x0) + uy * (b.y0 - f.y0), t1 = ux * (b.x1 - f.x0) + uy * (b.y1 - f.y0);
    const double overlap = std::min(fl, std::max(t0, t1)) - std::max(0.0, std::min(t0, t1));
    return overlap >= 0.5 * std::min(fl, bl);
}

// layers::segment_distance(x, y, b) < r, by closer_than.
bool passes_near(const Bridge& b, double x, double y, double r) {
    double ox, oy;
    layers::segment_offset(x, y, b.x0, b.y0, b.x1, b.y1, ox, oy);
    return closer_than(ox, oy, r);
}

// Whether the box around b's ends, grown by m, meets the box around
// (x0, y0), (x1, y1): no point of b comes within m of that segment otherwise.
bool boxes_meet(const Bridge& b, double x0, double y0, double x1, double y1, double m) {
    return std::min(b.x0, b.x1) - m <= std::max(x0, x1) && std::min(x0, x1) <= std::max(b.x0, b.x1) + m &&
           std::min(b.y0, b.y1) - m <= std::max(y0, y1) && std::min(y0, y1) <= std::max(b.y0, b.y1) + m;
}

// How far in height a forbidden place and bar reach.
double place_window(double layer_height) { return kPlaceLayers * layer_height + 1e-9; }
double bar_window(double layer_height) { return 1.5 * layer_height; }

bool near_place(const Xyz& f, const Bridge& b, double layer_height) {
    return std::abs(f.z - b.z) < place_window(layer_height) && boxes_meet(b, f.x, f.y, f.x, f.y, kPlaceNear) &&
           passes_near(b, f.x, f.y, kPlaceNear);
}

bool near_bar(const Bridge& f, const Bridge& b, double layer_height) {
    auto near = [](double ax, double ay, double bx, double by) { return closer_than(ax - bx, ay - by, kForbiddenNear); };
    // Ends within kForbiddenNear, or a stretch of b within kForbiddenBeside
    // of f (along: its ends that near f's line, their projections overlapping f).
    return std::abs(f.z - b.z) < bar_window(layer_height) &&
           boxes_meet(b, f.x0, f.y0, f.x1, f.y1, std::max(kForbiddenNear, kForbiddenBeside)) &&
           ((near(f.x0, f.y0, b.x0, b.y0) && near(f.x1, f.y1, b.x1, b.y1)) ||
            (near(f.x0, f.y0, b.x1, b.y1) && near(f.x1, f.y1, b.x0, b.y0)) || along(f, b));
}

}  // namespace

bool near_forbidden(const Forbidden& forbidden, const Bridge& b, double layer_height) {
    for (const Xyz& f : forbidden.places)
        if (near_place(f, b, layer_height)) return true;
    for (const Bridge& f : forbidden.bars)
        if (near_bar(f, b, layer_height)) return true;
    return false;
}

ForbiddenLookup::ForbiddenLookup(const Forbidden& forbidden, double layer_height)
    : bars_(forbidden.bars), places_(forbidden.places), h_(layer_height) {
    std::stable_sort(bars_.begin(), bars_.end(), [](const Bridge& a, const Bridge& b) { return a.z < b.z; });
    std::stable_sort(places_.begin(), places_.end(), [](const Xyz& a, const Xyz& b) { return a.z < b.z; });
}

template <class Place, class Bar>
bool ForbiddenLookup::any_in_windows(double z, Place place, Bar bar) const {
    const double pw = place_window(h_), bw = bar_window(h_);
    for (auto it = std::lower_bound(places_.begin(), places_.end(), z - pw,
                                    [](const Xyz& f, double zf) { return f.z < zf; });
         it != places_.end() && it->z <= z + pw; ++it)
        if (place(*it)) return true;
    for (auto it = std::lower_bound(bars_.begin(), bars_.end(), z - bw,
                                    [](const Bridge& f, double zf) { return f.z < zf; });
         it != bars_.end() && it->z <= z + bw; ++it)
        if (bar(*it)) return true;
    return false;
}

bool ForbiddenLookup::operator()(const Bridge& b) const {
    // Only those within their window of b's height can match (near_place and
    // near_bar test the same windows exactly): a bar search asks this of
    // every candidate.
    return any_in_windows(
        b.z, [&](const Xyz& f) { return near_place(f, b, h_); }, [&](const Bridge& f) { return near_bar(f, b, h_); });
}

bool ForbiddenLookup::any_near(double z, double x_lo, double y_lo, double x_hi, double y_hi) const {
    // Each test above needs the bar's box and the forbidden one's (grown by
    // the margin) to meet, and the bar lies within this box.
    auto meets = [&](double fx0, double fy0, double fx1, double fy1, double m) {
        return x_lo - m <= std::max(fx0, fx1) && std::min(fx0, fx1) <= x_hi + m && y_lo - m <= std::max(fy0, fy1) &&
               std::min(fy0, fy1) <= y_hi + m;
    };
    const double pw = place_window(h_), bw = bar_window(h_);
    return any_in_windows(
        z, [&](const Xyz& f) { return std::abs(f.z - z) < pw && meets(f.x, f.y, f.x, f.y, kPlaceNear); },
        [&](const Bridge& f) {
            return std::abs(f.z - z) < bw && meets(f.x0, f.y0, f.x1, f.y1, std::max(kForbiddenNear, kForbiddenBeside));
        });
}

Scaffold plan_scaffold(const overhang::SupportPoints& points, const layers::LayerStack& stack, const Obstacles& obs,
                       const Settings& s, const Forbidden& forbidden, std::shared_ptr<ModelAnswers> answers,
                       const std::function<const Cavities&()>& shared_cavities, BridgeReplay* replay,
                       const std::vector<const Obstacles*>& helper_obstacles) {
    // Layers by z without purge lines: the layer above a height.
    LayerIndex by_z;
    for (int i = 0; i < static_cast<int>(stack.layers.size()); ++i)
        if (!stack.layers[i].purge) by_z.by_z.emplace_back(stack.layers[i].z, i);
    std::stable_sort(by_z.by_z.begin(), by_z.by_z.end());

    // Bridge ends need a pillar that drop_pillar can really build.
    if (!answers) answers = std::make_shared<ModelAnswers>();
    if (!answers->bar_ends) answers->bar_ends = std::make_shared<BarEndAnswers>();
    if (!answers->lean_ins) answers->lean_ins = std::make_shared<LeanInAnswers>();
    if (!answers->descents) answers->descents = std::make_shared<DescentCache>();
    const std::shared_ptr<LeanInAnswers> lean_ins = answers->lean_ins;  // answers moves to the search below
    const std::shared_ptr<DescentCache> descents = answers->descents;
    auto view_of = [&](const Obstacles& o) {
        ModelView v = model_view(o);
        v.end_stands = [&stack, &s, &by_z, op = &o, known = answers->bar_ends](double x, double y, double z) {
            int above = by_z.above(z);
            return above >= 0 && bar_end_stands(x, y, above, stack, *op, s, *known);
        };
        return v;
    };
    ModelView m = view_of(obs);
    // The search's other threads ask the same model through caches of their own.
    std::vector<ModelView> helper_views;
    for (const Obstacles* o : helper_obstacles) helper_views.push_back(view_of(*o));
    std::vector<const ModelView*> helpers;
    for (const ModelView& v : helper_views) helpers.push_back(&v);
    // Bars that would be trapped in a hollow of the model are no bridges:
    // the hollows are mapped when the first bar is taken.
    std::optional<Cavities> cavities;
    const ForbiddenLookup near(forbidden, s.layer_height);
    auto is_forbidden = [&near](double z, double x0, double y0, double x1, double y1) {
        return near({x0, y0, x1, y1, z, {}, 0, 0});
    };
    if (!forbidden.empty()) {
        m.bar_forbidden = is_forbidden;
        m.forbidden_near = [&near](double z, double x_lo, double y_lo, double x_hi, double y_hi) {
            return near.any_near(z, x_lo, y_lo, x_hi, y_hi);
        };
    }
    m.bar_trapped = [&](double z, double x0, double y0, double x1, double y1) {
        if (is_forbidden(z, x0, y0, x1, y1)) return true;
        if (shared_cavities) return shared_cavities().bar_trapped(x0, y0, x1, y1, z);
        if (!cavities) cavities.emplace(stack, obs);
        return cavities->bar_trapped(x0, y0, x1, y1, z);
    };
    std::vector<Active> start;
    for (int i : canonical_order(points)) {
        const auto& p = points.points[i];
        const int t = tip_layer(stack, p.layer, s);
        if (t < 0) continue;  // nothing under it to stand a support on: left to drop_pillar below
        start.push_back({p.x, p.y, stack.layers[t].z, i});
    }
    BridgePlan plan = plan_bridges(start, m, s, 0, std::move(answers), replay, helpers, forbidden);
    Scaffold out;
    out.bridges = std::move(plan.bridges);
    out.columns = std::move(plan.connectors);
    std::vector<Active> rest = std::move(plan.remaining);
    // Points with no layer under them were never planned: they fall to pillars (and are dropped).
    std::vector<char> planned(points.points.size(), 0);
    for (const Active& a : start) planned[a.point] = 1;
    for (int i : canonical_order(points))
        if (!planned[i]) rest.push_back({points.points[i].x, points.points[i].y, points.points[i].z, i});
    // The remaining points and the bridge ends stand on the bed, on the model
    // or, branching, on a column already planned (a connector or pillar).
    Trunks trunks(stack, kBranchSteer);
    trunks.add(out.columns, stack, s);
    trunks.keep_descents(descents.get());
    for (const Active& a : rest) {
        int overhang_layer = a.point >= 0 ? points.points[a.point].layer : by_z.above(a.z);
        std::optional<std::vector<Column>> chain;
        if (overhang_layer >= 0 && a.point < 0)
            chain = drop_pillar(a.x, a.y, overhang_layer, Top::Bridge, stack, obs, s, &trunks, TipPlaces::Any, true, a.hold, a.give);
        if (overhang_layer >= 0 && a.point >= 0) chain = support_point(a.x, a.y, overhang_layer, stack, obs, s, &trunks, true, lean_ins.get());
        if (!chain) {
            if (a.point >= 0) out.dropped_points.push_back(a.point);
            else out.unheld_bridge_ends.push_back({a.x, a.y, a.z});
            continue;
        }
        trunks.add(*chain, stack, s);
        for (Column& col : *chain) {
            col.point = a.point;
            out.columns.push_back(col);
        }
    }
    std::sort(out.dropped_points.begin(), out.dropped_points.end());
    return out;
}

}  // namespace scaffold::plan
