#include "plan/candidates.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <thread>
#include <tuple>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/iterator/function_output_iterator.hpp>

#include "plan/stiffness.hpp"
#include "plan/workers.hpp"

namespace scaffold::plan {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {
constexpr double kEps = 1e-6;  // mm: the tolerance of snap_down, so a point is carried at its own height
// Bars' clearance: samples along a line this far apart (two cells at the
// default resolution), lines told apart to this (mm) across.
constexpr double kBarSample = 0.2;
constexpr double kLineOffset = 1e-4;
constexpr int kLowerHeights = 3;  // a blocked bar is retried this many height steps lower
// A seed's best bar is tested against the model only when it is the best of
// all (most never are); after this many blocked ones the seed tests every
// bar that would become its best while searching, bounding the re-searches
// (each one at a time). 2, not 4, since bars are tested by line samples: the
// same plans on the corpora, bunny 0.83 -> 0.79 and elephant 1.00 -> 0.95 of
// the time before those samples (0: every seed eager, 0.93 and 1.21).
constexpr int kLazyBars = 2;
// The same for the pillar searches under a bar's ends (half a plan's time
// when every seed asked them while searching): a seed asks them only when
// its best is the best of all, for every span it took on the way (so the
// best it found is the one it finds asking them as it goes); after this
// many such bests with an end that cannot stand, it asks as it goes.
// Bunny 772 -> 386 ms of planning, elephant 583 -> 450, the same plans on
// the corpora but figure.slic3r13's (its blocked bars learnt in another
// order): 774.8 -> 672.6 mm, passing.
constexpr int kLazyEnds = 1;
}  // namespace

double bridge_gain(int supported, double z, double length) { return (supported - 2) * z - length; }

double bridge_score(double gain, int supported, double l_max) { return gain - supported * l_max; }

double max_lean_per_layer(double h, const Settings& s) {
    double reach = h * std::tan(s.overhang_angle_deg * std::numbers::pi / 180) + s.support_width / 2;
    return std::min(kMaxLeanPerLayer * s.pillar_radius, reach);
}

double ModelView::snap_down(double z) const {
    if (layer_tops.empty()) return z;
    auto it = std::upper_bound(layer_tops.begin(), layer_tops.end(), z + 1e-6);
    return it == layer_tops.begin() ? -1 : *(it - 1);
}

std::vector<double> ModelView::tops_between(double z_lo, double z_hi, double layer_height) const {
    std::vector<double> out;
    if (layer_tops.empty()) {
        // Layers every layer_height from the bed.
        for (long i = std::lround(std::floor(z_lo / layer_height + 1e-6)) + 1; static_cast<double>(i) * layer_height <= z_hi + 1e-6; ++i)
            out.push_back(static_cast<double>(i) * layer_height);
        return out;
    }
    auto it = std::upper_bound(layer_tops.begin(), layer_tops.end(), z_lo + 1e-6);
    for (; it != layer_tops.end() && *it <= z_hi + 1e-6; ++it) out.push_back(*it);
    return out;
}

// Buffers of evaluate(), kept between calls so a search allocates once.
struct BridgeSearch::Scratch {
    struct Near {
        double du, adv, t, w;  // along, |across|, highest bar that carries it, across + its z
        double low;            // lowest bar that carries it
        int id;
        int miss0 = 0, miss1 = 0;  // heights no bar on this line carries it: miss_z[miss0, miss1)
    };
    std::vector<Near> pts;
    std::vector<double> miss_z;
    std::vector<int> hits, left, right, reach, gbeg, gend, count, by_t;
    std::vector<char> carried;  // carries(i, z) at the current height
    std::vector<signed char> stands;
    std::vector<double> heights, wl, wr, ws;
    // The same counts and largest w for the lower heights a blocked span is
    // tried at (j = 1 .. kLowerHeights - 1), made when first asked at a height.
    struct Lower {
        double z = 0;
        bool ready = false;
        bool rejected = false;   // the line may hold a rejected bar at z
        bool forbidden = false;  // or a forbidden one
        std::vector<int> count;
        std::vector<double> wl, wr;
    };
    std::vector<Lower> lower;
    const ModelView* model = nullptr;  // the model as this thread asks it
    // Bars' clearance by samples along their line (bar_clear): per line
    // (direction, offset) and layer, whether each sample's disc is clear
    // (0 not asked, 1 clear, 2 blocked), sample j at j * kBarSample along it.
    struct LineSamples {
        long j0 = 0;
        std::vector<signed char> state;
    };
    std::unordered_map<BarKey, LineSamples, BarKeyHash> lines;
    // The shared answers this thread has seen (ends_, bars_ of ModelAnswers),
    // asked here first: the shared tables are behind a lock the threads
    // would otherwise take for every end and bar they scan.
    BarTable<bool> ends_seen, bars_seen;
};

struct BridgeSearch::Index {
    using Point = bg::model::point<double, 2, bg::cs::cartesian>;
    using Box = bg::model::box<Point>;
    using Value = std::pair<Point, int>;
    bgi::rtree<Value, bgi::rstar<16>> tree;

    // Ids in the box, in the tree's order: callers must not depend on it.
    void in_box(double x0, double y0, double x1, double y1, std::vector<int>& ids) const {
        ids.clear();
        tree.query(bgi::intersects(Box(Point(x0, y0), Point(x1, y1))),
                   boost::make_function_output_iterator([&](const Value& v) { ids.push_back(v.second); }));
    }
    std::vector<int> in_box(double x0, double y0, double x1, double y1) const {
        std::vector<int> ids;
        in_box(x0, y0, x1, y1, ids);
        return ids;
    }
};

BridgeSearch::BridgeSearch(const ModelView& model, const Settings& settings, int threads,
                           std::shared_ptr<ModelAnswers> answers, std::vector<const ModelView*> helpers)
    : model_(&model), helpers_(std::move(helpers)), s_(settings),
      answers_(answers ? std::move(answers) : std::make_shared<ModelAnswers>()), index_(std::make_shared<Index>()) {
    reach_ = std::hypot(s_.bridge_max_length, s_.bridge_max_offset) + 1e-6;
    // By default a second thread only without model queries: with them, on
    // real prints, the queries behind their one lock dominate and the
    // threads wait on each other (a 1204-point anchor: 12.3 s on two
    // threads, 10.3 s on one). With a view of the model of its own per
    // thread, one thread per view.
    if (!helpers_.empty()) threads = static_cast<int>(helpers_.size()) + 1;
    if (threads <= 0) threads = model_->disc_clear ? 1 : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads_ = std::min(threads, kMaxPlanThreads);
    helpers_.resize(std::min<std::size_t>(helpers_.size(), static_cast<std::size_t>(threads_ - 1)));
    for (int t = 0; t < threads_; ++t) scratch_.push_back(std::make_shared<Scratch>());
}

namespace {

// std::lround(v * 1000), inline: for |v * 1000| < 2^52 adding a half is
// exact, so truncating it rounds halves away from zero just the same (a
// library call per coordinate was a twentieth of a plan's time).
long microns(double v) {
    const double m = v * 1000;
    return static_cast<long>(m >= 0 ? m + 0.5 : m - 0.5);
}

// The sweep direction (of D, as evaluate() numbers them) a bar from
// (x0, y0) to (x1, y1) lies along, that direction's unit vector (c, sn) and
// the bar's offset v across it.
struct SweepLine {
    int k;
    double c, sn, v;
};
SweepLine sweep_line(double x0, double y0, double x1, double y1, int D) {
    double th = std::atan2(y1 - y0, x1 - x0);
    if (th < 0) th += std::numbers::pi;
    const int k = static_cast<int>(std::lround(th * D / std::numbers::pi)) % D;
    const double a = k * std::numbers::pi / D, c = std::cos(a), sn = std::sin(a);
    return {k, c, sn, -x0 * sn + y0 * c};
}

// rejected_lines_: 2^16 bits; a line's offset bucketed this finely (mm),
// its neighbours asked too: the same bar (the same key, its ends to the
// micron) lies on lines a micron or two apart at most.
constexpr std::size_t kRejectLineBits = std::size_t{1} << 16;
constexpr double kRejectLineTol = 0.01;

std::size_t reject_line_bit(int direction, long bucket, long z_microns) {
    return BarKeyHash{}(BarKey{direction, bucket, z_microns, 0, 0}) & (kRejectLineBits - 1);
}

}  // namespace

BridgeSearch::BridgeSearch(const BridgeSearch& o, const ModelView& model, std::vector<const ModelView*> helpers)
    : model_(&model), helpers_(std::move(helpers)), s_(o.s_), reach_(o.reach_), points_(o.points_), low_(o.low_),
      alive_(o.alive_), seeds_(o.seeds_),
      dirty_(o.dirty_), ranked_(o.ranked_), rejected_(o.rejected_), rejected_lines_(o.rejected_lines_),
      answers_(o.answers_), misses_(o.misses_),
      evaluations_(o.evaluations_), index_(std::make_shared<Index>(*o.index_)), threads_(o.threads_) {
    // Views for as many threads as the original had, or none.
    if (helpers_.size() + 1 != static_cast<std::size_t>(threads_)) helpers_.clear();
    for (int t = 0; t < threads_; ++t) scratch_.push_back(std::make_shared<Scratch>());
}

std::unique_ptr<BridgeSearch> BridgeSearch::clone(const ModelView& model, std::vector<const ModelView*> helpers) const {
    return std::unique_ptr<BridgeSearch>(new BridgeSearch(*this, model, std::move(helpers)));
}

BridgeSearch::Key BridgeSearch::key_of(double x0, double y0, double x1, double y1, double z) {
    auto r = [](double v) { return microns(v); };
    // The same bar from either end is the same bar.
    if (std::make_pair(r(x1), r(y1)) < std::make_pair(r(x0), r(y0))) {
        std::swap(x0, x1);
        std::swap(y0, y1);
    }
    return {r(x0), r(y0), r(x1), r(y1), r(z)};
}

double connector_compliance(const Active& a, double bar_z, double bar_length, const Settings& s) {
    const double top = std::max(a.z, a.hold);
    const double stick = ring_compliance(kConnectorRadius, 0, top, bar_z + kBarThickness, a.z, s.support_width, s.modulus);
    // The bar's own layers under it, bent about the bar's long axis.
    const double h_hi = top - bar_z, h_lo = top - bar_z - kBarThickness;
    const double bar = (h_hi * h_hi * h_hi - h_lo * h_lo * h_lo) /
                       (3 * s.modulus * bar_inertia(bar_length, s.support_width, s.pillar_radius));
    return stick + bar;
}

double connector_allowance(const Settings& s) {
    const double target = target_stiffness(s);
    return target > 0 ? 0.5 / target : 0;
}

double lowest_carrying_bar(const Active& a, const Settings& s) {
    if (!(connector_allowance(s) > 0)) return 0;
    const double allowed = connector_allowance(s) - a.give;
    // The longest bar is the stiffest: a bar is offered by this bound and
    // judged with its own length when its connectors are placed.
    auto fits = [&](double z) {
        return z + kBarThickness >= a.z || connector_compliance(a, z, s.bridge_max_length, s) <= allowed;
    };
    if (fits(0)) return 0;
    // The connector gives less the shorter it is: the least z that fits.
    double lo = 0, hi = a.z;
    for (int i = 0; i < 50; ++i) (fits((lo + hi) / 2) ? hi : lo) = (lo + hi) / 2;
    return hi - 1e-7;  // a bar on the boundary still offered: the planner decides
}

int BridgeSearch::add(const Active& a) {
    int id = size();
    points_.push_back(a);
    low_.push_back(lowest_carrying_bar(a, s_));
    alive_.push_back(1);
    misses_.emplace_back();
    seeds_.resize(seeds_.size() + static_cast<std::size_t>(s_.sweep_directions));
    index_->tree.insert({Index::Point(a.x, a.y), id});
    mark_around(a.x, a.y);  // its own seeds, and those whose window it enters
    return id;
}

void BridgeSearch::remove(int id) {
    if (!alive_[id]) return;
    alive_[id] = 0;
    index_->tree.remove(Index::Value{Index::Point(points_[id].x, points_[id].y), id});
    for (int k = 0; k < s_.sweep_directions; ++k) {
        Seed& sd = seeds_[static_cast<std::size_t>(id * s_.sweep_directions + k)];
        if (sd.has) ranked_.erase({-sd.best.score, id * s_.sweep_directions + k});
        sd.has = false;
        sd.dirty = false;
    }
    mark_around(points_[id].x, points_[id].y);
}

// Seeds whose window (30 mm along their sweep line, 5 mm across) holds (x, y).
void BridgeSearch::mark_around(double x, double y, double margin) {
    const int D = s_.sweep_directions;
    const double r = reach_ + margin;
    for (int id : index_->in_box(x - r, y - r, x + r, y + r)) {
        double dx = x - points_[id].x, dy = y - points_[id].y;
        for (int k = 0; k < D; ++k) {
            int seed = id * D + k;
            if (seeds_[seed].dirty) continue;
            double th = k * std::numbers::pi / D;
            double du = dx * std::cos(th) + dy * std::sin(th), dv = -dx * std::sin(th) + dy * std::cos(th);
            if (std::abs(du) > s_.bridge_max_length + margin + 1e-6 || std::abs(dv) > s_.bridge_max_offset + margin + 1e-6)
                continue;
            seeds_[seed].dirty = true;
            dirty_.push_back(seed);
        }
    }
}

template <class Ask>
bool BridgeSearch::answer(BarTable<bool>& table, BarTable<bool>& seen, const Key& key, Ask ask) {
    if (threads_ > 1)
        if (const bool* known = seen.find(key)) return *known;
    bool ok = answer(table, key, ask);
    if (threads_ > 1) seen.insert(key, ok);
    return ok;
}

template <class Ask>
bool BridgeSearch::answer(BarTable<bool>& table, const Key& key, Ask ask) {
    auto lock = model_lock();
    if (const bool* known = table.find(key)) return *known;
    // Each thread asks a view of its own: only the answers are shared.
    if (!helpers_.empty()) lock.unlock();
    const bool ok = ask();
    if (!helpers_.empty()) lock.lock();
    table.insert(key, ok);  // the same answer, should another thread have stored it meanwhile
    return ok;
}

void BridgeSearch::stale_near(double x0, double y0, double x1, double y1) {
    // A bar near or along it has an end within a millimetre of it, or lies
    // over it (kForbiddenNear, kForbiddenBeside): every seed whose window
    // reaches within 2 mm of a point of it, sampled every millimetre.
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int n = std::max(1, static_cast<int>(std::ceil(len)));
    for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        mark_around(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, 2.0);
    }
}

bool BridgeSearch::bar_clear(const ModelView& mv, Scratch& sc, double x0, double y0, double x1, double y1, double z) {
    if (!mv.segment_clear) return true;
    return answer(answers_->bars, sc.bars_seen, key_of(x0, y0, x1, y1, z), [&] {
        // The bar fills the layers up to kBarThickness above z; its ends reach
        // into the pillar tops, so the whole pillar radius keeps the gap.
        std::vector<double> layers = mv.tops_between(z, z + kBarThickness, s_.layer_height);
        if (layers.empty()) return false;
        const double r = s_.pillar_radius + s_.xy_gap;
        if (!mv.disc_clear) {
            for (double zl : layers)
                if (!mv.segment_clear(zl, x0, y0, x1, y1, r)) return false;
            return true;
        }
        // The bars a search asks about lie on a few lines (bunny: 105,000
        // bars on 4,800 lines and heights): discs at fixed samples along the
        // line, kBarSample apart, each asked once for all the bars over it,
        // and at the bar's own two ends; no sample past an end. So a bar is
        // sampled as densely as when it sampled its own length every two
        // cells (segment_clear, still asked where the view has no disc test).
        const SweepLine along = sweep_line(x0, y0, x1, y1, s_.sweep_directions);
        const int k = along.k;
        const double c = along.c, sn = along.sn;
        const long v_key = std::lround(along.v / kLineOffset);
        const double v = static_cast<double>(v_key) * kLineOffset;
        double ua = x0 * c + y0 * sn, ub = x1 * c + y1 * sn;
        if (ua > ub) std::swap(ua, ub);
        // The samples within the bar, and its two ends.
        const long j0 = static_cast<long>(std::ceil(ua / kBarSample)), j1 = static_cast<long>(std::floor(ub / kBarSample));
        for (double zl : layers) {
            if (!mv.disc_clear(zl, x0, y0, r) || !mv.disc_clear(zl, x1, y1, r)) return false;
            if (j1 < j0) continue;
            Scratch::LineSamples& line = sc.lines[Key{k, v_key, microns(zl), 0, 0}];
            if (line.state.empty()) line.j0 = j0;
            if (j0 < line.j0) {
                line.state.insert(line.state.begin(), static_cast<std::size_t>(line.j0 - j0), 0);
                line.j0 = j0;
            }
            if (j1 - line.j0 + 1 > static_cast<long>(line.state.size()))
                line.state.resize(static_cast<std::size_t>(j1 - line.j0 + 1), 0);
            for (long j = j0; j <= j1; ++j) {
                signed char& st = line.state[static_cast<std::size_t>(j - line.j0)];
                if (st == 0) {
                    const double u = static_cast<double>(j) * kBarSample;
                    st = mv.disc_clear(zl, u * c - v * sn, u * sn + v * c, r) ? 1 : 2;
                }
                if (st == 2) return false;
            }
        }
        return true;
    });
}

// Whether a pillar can stand under a bridge end (the model view's test,
// asked once per end): a span with an end that cannot stand is no candidate,
// rather than a best that is taken, fails and is rejected one at a time
// (elephant: 17,000 such rejects before this test moved here).
bool BridgeSearch::end_stands(const ModelView& mv, Scratch& sc, double x, double y, double z) {
    if (!mv.end_stands) return true;
    return answer(answers_->ends, sc.ends_seen, Key{microns(x), microns(y), microns(z), 0, 0},
                  [&] { return mv.end_stands(x, y, z); });
}

void BridgeSearch::no_connector(int id, const Candidate& c) {
    const int D = s_.sweep_directions;
    const int k = c.seed % D;
    const Active& q = points_[c.seed / D];
    const double th = k * std::numbers::pi / D;
    misses_[id].push_back({k, -q.x * std::sin(th) + q.y * std::cos(th), c.z});
}

// The best bridge on the sweep line of direction k through point id, among
// those whose span contains the point. The line meets the anchoring segment
// (5 mm either side, along the sweep) of every point in the band, at the
// point's own position along the line: those are the candidate ends.
// Touches only seeds_[seed] and sc (the caller ranks it): safe on any thread.
void BridgeSearch::evaluate(int seed, Scratch& sc) {
    const int D = s_.sweep_directions;
    const int id = seed / D, k = seed % D;
    Seed& sd = seeds_[seed];
    sd.dirty = false;
    sd.has = false;
    if (!alive_[id]) return;

    const double L = s_.bridge_max_length, O = s_.bridge_max_offset;
    const double th = k * std::numbers::pi / D, c = std::cos(th), sn = std::sin(th);
    const Active& q = points_[id];
    const double uq = q.x * c + q.y * sn, vq = -q.x * sn + q.y * c;
    const double hx = L * std::abs(c) + O * std::abs(sn), hy = L * std::abs(sn) + O * std::abs(c);
    // Whether a span of this seed at height z may be forbidden (every span
    // lies in the window's box).
    auto forbidden_at = [&](double z) {
        return model_->bar_forbidden && (!model_->forbidden_near || model_->forbidden_near(z, q.x - hx - 1e-6, q.y - hy - 1e-6,
                                                                                            q.x + hx + 1e-6, q.y + hy + 1e-6));
    };
    const double lean_per_mm = max_lean_per_layer(s_.layer_height, s_) / s_.layer_height;

    using Near = Scratch::Near;
    std::vector<Near>& pts = sc.pts;
    pts.clear();
    sc.miss_z.clear();
    index_->in_box(q.x - hx, q.y - hy, q.x + hx, q.y + hy, sc.hits);
    for (int p : sc.hits) {
        const Active& a = points_[p];
        double du = a.x * c + a.y * sn - uq, adv = std::abs(-a.x * sn + a.y * c - vq);
        if (std::abs(du) > L + 1e-6 || adv > O + 1e-6) continue;
        // Carried when at least the drop above the bar, and its connector
        // from the bar's top leans no more than printable (its first loop
        // stands straight on the bar, planner.cpp's connector_to).
        double t = std::min(a.z - s_.bridge_min_drop,
                            a.z - kBarThickness - (adv > 0 ? s_.layer_height + adv / lean_per_mm : 0.0));
        const int m0 = static_cast<int>(sc.miss_z.size());
        for (const Miss& ms : misses_[p])
            if (ms.direction == k && std::abs(ms.v - vq) < kEps) sc.miss_z.push_back(ms.z);
        pts.push_back({du, adv, t, adv + a.z, low_[p], p, m0, static_cast<int>(sc.miss_z.size())});
    }
    // Whether a bar at height z on this line carries pts[i].
    auto carries = [&](int i, double z) {
        const Near& p = pts[i];
        if (p.t < z - kEps || z < p.low) return false;
        for (int m = p.miss0; m < p.miss1; ++m)
            if (std::abs(sc.miss_z[m] - z) < kEps) return false;
        return true;
    };
    const int n = static_cast<int>(pts.size());
    if (n < 3) return;
    // Along the line, ties by id: not by the tree's order, which depends on its history.
    std::sort(pts.begin(), pts.end(), [](const Near& a, const Near& b) { return std::tie(a.du, a.id) < std::tie(b.du, b.id); });

    // Ends: a on the left (du <= 0, first of its equal-du group), b on the
    // right (du >= 0, last of its group), so [a..b] is exactly the span.
    // Exact comparisons: the point itself is at du = 0 exactly.
    std::vector<int>&left = sc.left, &right = sc.right;
    left.clear();
    right.clear();
    for (int i = 0; i < n; ++i) {
        if (pts[i].du <= 0 && (i == 0 || pts[i - 1].du < pts[i].du)) left.push_back(i);
        if (pts[i].du >= 0 && (i == n - 1 || pts[i + 1].du > pts[i].du)) right.push_back(i);
    }
    std::reverse(left.begin(), left.end());  // outward from the point
    int a_max = -1, b_min = n;  // last point at du <= 0, first at du >= 0 (the point itself is at 0)
    for (int i = 0; i < n; ++i) {
        if (pts[i].du <= 0) a_max = i;
        if (pts[i].du >= 0 && b_min == n) b_min = i;
    }
    // reach[a]: the last point a span from a can end at (30 mm on).
    std::vector<int>& reach = sc.reach;
    reach.resize(n);
    for (int i = 0, j = 0; i < n; ++i) {
        while (j + 1 < n && pts[j + 1].du - pts[i].du <= L + kEps) ++j;
        reach[i] = j;
    }
    // Each end's group of points at the same du: [gbeg[i], gend[i]].
    std::vector<int>&gbeg = sc.gbeg, &gend = sc.gend;
    gbeg.resize(n);
    gend.resize(n);
    for (int i = 0; i < n; ++i) gbeg[i] = i > 0 && pts[i - 1].du == pts[i].du ? gbeg[i - 1] : i;
    for (int i = n - 1; i >= 0; --i) gend[i] = i < n - 1 && pts[i + 1].du == pts[i].du ? gend[i + 1] : i;

    // Candidate heights: where each point stops being carried, snapped to a layer top.
    std::vector<double>& heights = sc.heights;
    heights.clear();
    for (const Near& p : pts) {
        double z = model_->snap_down(p.t);
        if (z > kEps) heights.push_back(z);
    }
    std::sort(heights.begin(), heights.end(), std::greater<>());
    heights.erase(std::unique(heights.begin(), heights.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }),
                  heights.end());

    Candidate best;
    bool has = false;
    const bool ends_eager = sd.ends_failed >= kLazyEnds;
    sd.takes.clear();
    int best_a = -1, best_b = -1;  // best's span: its carried list is built once, at the end
    std::vector<int>& count = sc.count;
    std::vector<double>&wl = sc.wl, &wr = sc.wr;  // count, wl, wr: made per height (carried_at)
    sc.lower.resize(kLowerHeights);
    auto take = [&](int a, int b, double z, int kk, double wmax) {
        double len = pts[b].du - pts[a].du;
        best.x0 = (uq + pts[a].du) * c - vq * sn;
        best.y0 = (uq + pts[a].du) * sn + vq * c;
        best.x1 = (uq + pts[b].du) * c - vq * sn;
        best.y1 = (uq + pts[b].du) * sn + vq * c;
        best.z = z;
        best.gain = bridge_gain(kk, z, len);
        best.l_max = wmax - z;
        best.score = bridge_score(best.gain, kk, best.l_max);
        best.seed = seed;
        best.end0 = pts[a].id;
        best.end1 = pts[b].id;
        best_a = a;
        best_b = b;
        has = true;
        if (!ends_eager) sd.takes.push_back({best.x0, best.y0, best.x1, best.y1, z});
    };
    const bool eager = sd.blocked >= kLazyBars;
    // `blocked` is set when the model blocks the bar itself.
    // Whether a pillar stands under each end at the height being scanned
    // (by point index; 0 not asked yet, 1 yes, 2 no): an end is asked for
    // many spans, and the shared answers are behind a lock and a hash.
    std::vector<signed char>& stands = sc.stands;
    double stands_z = -1;
    // `rejected`: whether this line may hold a rejected bar at z,
    // `forbidden`: a forbidden one.
    auto usable = [&](int a, int b, double z, bool rejected, bool forbidden, bool& blocked) {
        double x0 = (uq + pts[a].du) * c - vq * sn, y0 = (uq + pts[a].du) * sn + vq * c;
        double x1 = (uq + pts[b].du) * c - vq * sn, y1 = (uq + pts[b].du) * sn + vq * c;
        blocked = false;
        // The bar before the ends when the bar is tested here at all: a
        // blocked bar spares the pillar searches under its ends.
        if (rejected && rejected_.contains(key_of(x0, y0, x1, y1, z))) return false;
        // Turned down as offered, one at a time, each such bar cost the seeds
        // offering it a search again (bunny: about 2000 searches of one seed
        // over five plans); left out here, the same bar is the best allowed.
        if (forbidden && model_->bar_forbidden(z, x0, y0, x1, y1)) return false;
        if (eager && !bar_clear(*sc.model, sc, x0, y0, x1, y1, z)) {
            blocked = true;
            return false;
        }
        if (z != stands_z) {
            stands.assign(n, 0);
            stands_z = z;
        }
        auto end_ok = [&](int i, double x, double y) {
            if (!stands[i]) stands[i] = end_stands(*sc.model, sc, x, y, z) ? 1 : 2;
            return stands[i] == 1;
        };
        return !ends_eager || (end_ok(a, x0, y0) && end_ok(b, x1, y1));
    };

    // Points by the highest bar that carries them, to grow the carried set
    // as the height goes down.
    std::vector<int>& by_t = sc.by_t;
    by_t.resize(n);
    for (int i = 0; i < n; ++i) by_t[i] = i;
    // Ties by position: the order of a stable sort, without its buffer.
    std::sort(by_t.begin(), by_t.end(), [&](int a, int b) { return pts[a].t > pts[b].t || (pts[a].t == pts[b].t && a < b); });
    std::vector<double>& ws = sc.ws;  // w of the points carried at the current height, ascending
    ws.clear();
    std::size_t next = 0;
    for (double z : heights) {
        while (next < by_t.size() && pts[by_t[next]].t >= z - kEps) {
            double w = pts[by_t[next++]].w;
            ws.insert(std::upper_bound(ws.begin(), ws.end(), w), w);
        }
        if (ws.size() < 3) continue;
        // No bridge at this height can beat the best so far: k carried
        // points have l_max >= (k-th smallest w) - z, so the score is at
        // most (k - 2) z - min length - k (w_k - z).
        // (Skipped only when every k's bound is at most the best: the first
        // one above it settles the question.)
        if (has) {
            bool may_beat = false;
            for (std::size_t kk = 3; kk <= ws.size() && !may_beat; ++kk) {
                double kd = static_cast<double>(kk);
                may_beat = (kd - 2) * z - s_.bridge_min_length - kd * (ws[kk - 1] - z) > best.score;
            }
            if (!may_beat) continue;
        }
        // Who is carried at height zc, asked once per point, not per pass:
        // cnt[i] carried before i; wl_[a]: largest w carried in [a..a_max];
        // wr_[b]: in [b_min..b]. The two overlap only on points at du = 0,
        // so together they cover [a..b].
        auto carried_at = [&](double zc, std::vector<int>& cnt, std::vector<double>& wl_, std::vector<double>& wr_) {
            std::vector<char>& car = sc.carried;
            car.resize(n);
            cnt.resize(n + 1);
            wl_.resize(n);
            wr_.resize(n);
            cnt[0] = 0;
            for (int i = 0; i < n; ++i) car[i] = carries(i, zc);
            for (int i = 0; i < n; ++i) cnt[i + 1] = cnt[i] + car[i];
            double m = 0;
            for (int i = a_max; i >= 0; --i) {
                if (car[i]) m = std::max(m, pts[i].w);
                wl_[i] = m;
            }
            m = 0;
            for (int i = b_min; i < n; ++i) {
                if (car[i]) m = std::max(m, pts[i].w);
                wr_[i] = m;
            }
        };
        carried_at(z, count, wl, wr);
        const bool rejected_here = line_may_hold_rejected(k, vq, z), forbidden_here = forbidden_at(z);
        // The lower heights a blocked span is tried at, counted when first needed.
        for (int j = 1; j < kLowerHeights; ++j) {
            sc.lower[j].z = model_->snap_down(z - j * s_.bridge_height_step);
            sc.lower[j].ready = false;
        }
        // With k carried, largest w at least W and length at least len, a
        // span scores at most k (2z - W) - 2z - len, largest at k = 3 or at
        // the most points there are: the bound that lets a span, or all
        // longer spans from the same left end, be skipped.
        auto cap = [&](int k_lo, int k_hi, double w, double len) {
            double slope = 2 * z - w;
            return std::max(k_lo * slope, k_hi * slope) - 2 * z - len;
        };
        // An end with nothing carried at it loses to the next end inwards
        // (same points, shorter), unless that one is too short or was rejected.
        // (A bar the search leaves out as forbidden counts as rejected here:
        // offered, it would have been, and the longer span taken instead.)
        auto rejected_span = [&](int a, int b) {
            if (!rejected_here && !forbidden_here) return false;
            double x0 = (uq + pts[a].du) * c - vq * sn, y0 = (uq + pts[a].du) * sn + vq * c;
            double x1 = (uq + pts[b].du) * c - vq * sn, y1 = (uq + pts[b].du) * sn + vq * c;
            return (rejected_here && rejected_.contains(key_of(x0, y0, x1, y1, z))) ||
                   (forbidden_here && model_->bar_forbidden(z, x0, y0, x1, y1));
        };
        // A bar over a blocked one is blocked too: at this height, with the
        // left ends taken outwards, every bar reaching right to
        // blocked_from or beyond contains a bar found blocked (eager seeds
        // would otherwise look up thousands of such bars one by one).
        double blocked_from = std::numeric_limits<double>::infinity();
        std::array<double, kLowerHeights> blocked_lower;  // the same for each retry height below
        blocked_lower.fill(std::numeric_limits<double>::infinity());
        for (std::size_t ia = 0; ia < left.size(); ++ia) {
            const int a = left[ia];
            const int k_all = count[reach[a] + 1] - count[a];  // the most a span from a can carry
            if (k_all < 3) continue;
            if (has && cap(3, k_all, wl[a], std::max(s_.bridge_min_length, -pts[a].du)) <= best.score) continue;
            const int a_in = ia > 0 && count[gend[a] + 1] == count[a] ? left[ia - 1] : -1;
            for (std::size_t ib = 0; ib < right.size(); ++ib) {
                const int b = right[ib];
                double len = pts[b].du - pts[a].du;
                if (len > L + kEps) break;
                if (len < s_.bridge_min_length - kEps) continue;
                int kk = count[b + 1] - count[a];
                double wmax = std::max(wl[a], wr[b]);
                if (has && cap(std::max(kk, 3), k_all, wmax, len) <= best.score) break;
                if (kk < 3) continue;
                // The score first: it is arithmetic, the tests below look bars up.
                double gain = bridge_gain(kk, z, len);
                if (gain <= 0) continue;
                double score = bridge_score(gain, kk, wmax - z);
                if (has && score <= best.score) continue;
                if (a_in >= 0 && pts[b].du - pts[a_in].du >= s_.bridge_min_length - kEps && !rejected_span(a_in, b))
                    continue;
                if (ib > 0 && count[b + 1] == count[gbeg[b]]) {
                    int b_in = right[ib - 1];
                    if (pts[b_in].du - pts[a].du >= s_.bridge_min_length - kEps && !rejected_span(a, b_in)) continue;
                }
                bool blocked = eager && pts[b].du >= blocked_from;
                if (!blocked && usable(a, b, z, rejected_here, forbidden_here, blocked)) {
                    take(a, b, z, kk, wmax);
                    continue;
                }
                if (blocked) blocked_from = std::min(blocked_from, pts[b].du);
                // Blocked (by the model or a failed check): the same span a few steps lower.
                for (int j = 1; j < kLowerHeights; ++j) {
                    Scratch::Lower& lo = sc.lower[j];
                    const double z2 = lo.z;
                    if (z2 <= kEps) break;
                    if (!lo.ready) {
                        carried_at(z2, lo.count, lo.wl, lo.wr);
                        lo.rejected = line_may_hold_rejected(k, vq, z2);
                        lo.forbidden = forbidden_at(z2);
                        lo.ready = true;
                    }
                    const int k2 = lo.count[b + 1] - lo.count[a];
                    const double w2 = std::max(lo.wl[a], lo.wr[b]);
                    double g2 = bridge_gain(k2, z2, len);
                    if (g2 <= 0) continue;
                    if (has && bridge_score(g2, k2, w2 - z2) <= best.score) continue;
                    bool blocked2 = eager && pts[b].du >= blocked_lower[j];
                    if (!blocked2 && usable(a, b, z2, lo.rejected, lo.forbidden, blocked2)) {
                        take(a, b, z2, k2, w2);
                        break;
                    }
                    if (blocked2) blocked_lower[j] = std::min(blocked_lower[j], pts[b].du);
                }
            }
        }
    }
    if (!has) return;
    for (int i = best_a; i <= best_b; ++i)
        if (carries(i, best.z)) best.carried.push_back(pts[i].id);
    std::sort(best.carried.begin(), best.carried.end());
    sd.best = std::move(best);
    sd.has = true;
    sd.bar_checked = eager;
}

// Seeds a thread must have to be worth starting: a thread costs its start
// and, on a busy machine, a wait in the join for a core (measured: with 32,
// 2 threads were slower than 1 while another build ran on the other core).
constexpr std::size_t kSeedsPerThread = 128;
// The same for threads with a model view of their own, which never wait on
// each other's model queries.
constexpr std::size_t kSeedsPerOwnThread = 16;

void BridgeSearch::evaluate_all(const std::vector<int>& seeds) {
    for (int seed : seeds) {
        Seed& sd = seeds_[seed];
        if (sd.has) ranked_.erase({-sd.best.score, seed});
        if (alive_[seed / s_.sweep_directions]) ++evaluations_;
    }
    const int threads = static_cast<int>(
        std::min<std::size_t>(threads_, seeds.size() / (helpers_.empty() ? kSeedsPerThread : kSeedsPerOwnThread)));
    for (int t = 0; t < threads_; ++t) scratch_[t]->model = &model_of(t);
    if (threads <= 1) {
        for (int seed : seeds) evaluate(seed, *scratch_[0]);
    } else {
        // Small chunks taken in turn, so threads slowed by a busy core still end together.
        std::atomic<std::size_t> next{0};
        constexpr std::size_t kChunk = 8;
        // An error in a model callback reaches the caller as it would on
        // one thread, and stops the others early.
        run_workers(threads, [&](int t) {
            try {
                for (std::size_t i; (i = next.fetch_add(kChunk)) < seeds.size();)
                    for (std::size_t j = i; j < std::min(seeds.size(), i + kChunk); ++j) evaluate(seeds[j], *scratch_[t]);
            } catch (...) {
                next = seeds.size();
                throw;
            }
        });
    }
    for (int seed : seeds)
        if (seeds_[seed].has) ranked_.insert({-seeds_[seed].best.score, seed});
}

void BridgeSearch::refresh() {
    std::vector<int> todo;
    todo.swap(dirty_);
    std::sort(todo.begin(), todo.end());
    // A seed removed and marked again is listed twice: once is enough.
    todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
    todo.erase(std::remove_if(todo.begin(), todo.end(), [&](int seed) { return !seeds_[seed].dirty; }), todo.end());
    evaluate_all(todo);
}

std::optional<Candidate> BridgeSearch::best() {
    for (;;) {
        refresh();
        if (ranked_.empty()) return std::nullopt;
        int seed = ranked_.begin()->second;
        Seed& sd = seeds_[seed];
        const Candidate& c = sd.best;
        Key key = key_of(c.x0, c.y0, c.x1, c.y1, c.z);
        // Another seed's bridge on the same line may have been rejected since.
        bool ok = !rejected_.contains(key);
        if (ok && !sd.bar_checked) {
            ok = bar_clear(*model_, *scratch_[0], c.x0, c.y0, c.x1, c.y1, c.z);
            if (ok) sd.bar_checked = true;
            else {
                mark_rejected(c.x0, c.y0, c.x1, c.y1, c.z);
                ++sd.blocked;
            }
        }
        // After the bar (a blocked bar spares the pillar searches): a span
        // taken on the way whose end cannot stand would not have been
        // taken, and the seed finds another best asking as it goes.
        if (ok && !sd.takes.empty()) {
            for (const auto& t : sd.takes)
                if (ok) ok = end_stands(t[0], t[1], t[4]) && end_stands(t[2], t[3], t[4]);
            if (ok) sd.takes.clear();
            else ++sd.ends_failed;
        }
        if (ok) return c;
        sd.dirty = true;
        dirty_.push_back(seed);
    }
}

void BridgeSearch::mark_rejected(double x0, double y0, double x1, double y1, double z) {
    rejected_.insert(key_of(x0, y0, x1, y1, z), 1);
    // Its line as evaluate() has it for the seeds on it.
    const SweepLine line = sweep_line(x0, y0, x1, y1, s_.sweep_directions);
    if (rejected_lines_.empty()) rejected_lines_.assign(kRejectLineBits / 64, 0);
    const std::size_t bit = reject_line_bit(line.k, static_cast<long>(std::floor(line.v / kRejectLineTol)), microns(z));
    rejected_lines_[bit / 64] |= std::uint64_t{1} << (bit % 64);
}

bool BridgeSearch::line_may_hold_rejected(int direction, double v, double z) const {
    if (rejected_lines_.empty()) return false;
    const long b = static_cast<long>(std::floor(v / kRejectLineTol)), zm = microns(z);
    for (long d = -1; d <= 1; ++d) {
        const std::size_t bit = reject_line_bit(direction, b + d, zm);
        if ((rejected_lines_[bit / 64] >> (bit % 64)) & 1u) return true;
    }
    return false;
}

void BridgeSearch::reject(const Candidate& c) {
    mark_rejected(c.x0, c.y0, c.x1, c.y1, c.z);
    if (c.seed >= 0 && !seeds_[c.seed].dirty) {
        seeds_[c.seed].dirty = true;
        dirty_.push_back(c.seed);
    }
}

}  // namespace scaffold::plan
