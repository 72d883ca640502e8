#pragma once
// Candidate bridges of the scaffolding (METHOD.md step 4): for each sweep
// direction and each active point, the bridges on the sweep line through the
// point, kept per (point, direction) and updated only where the active set
// changes, so the greedy planner does not rescan everything at each step.
// Pure geometry: the model is seen through ModelView, which tests fake.
#include <array>
#include <cstdint>
#include <limits>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "gcode/settings.hpp"

namespace scaffold::plan {

// A slanted connector's centre may move at most this fraction of the pillar
// radius between consecutive layers (0.5 mm at r = 1 over 0.2 mm layers, as
// the validator's reach h*tan(55 deg) + half a bead allows). On thinner
// layers that reach is smaller and is used instead (max_lean_per_layer).
inline constexpr double kMaxLeanPerLayer = 0.5;

// Thickness of a bridge bar (two layers); its connectors start on top of it.
inline constexpr double kBarThickness = 0.4;
// Radius of a slanted connector: it stays on the 0.9 mm wide bridge bar.
inline constexpr double kConnectorRadius = 0.75;

// Scoring of the method, exposed for tests.
double bridge_gain(int supported, double z, double length);
double bridge_score(double gain, int supported, double l_max);

// Largest sideways move of a connector's centre over one layer of height h.
double max_lean_per_layer(double h, const Settings& settings);

// What the planner asks about the model, by layer top z (not index), so a
// test can describe a model with a few lambdas. An empty function means "no
// model": everything is clear and pillars reach the bed.
struct ModelView {
    // Tops of the printed layers, ascending and distinct. Empty: layers every
    // settings.layer_height from 0, and heights are not snapped.
    std::vector<double> layer_tops;
    // The segment thickened by r is clear of the model on the layer with top z.
    std::function<bool(double z, double x0, double y0, double x1, double y1, double r)> segment_clear;
    // The disc is clear of the model on the layer with top z.
    std::function<bool(double z, double x, double y, double r)> disc_clear;
    // Top z of the highest model layer below z that touches the disc, or 0 (the bed).
    std::function<double(double z, double x, double y, double r)> model_top_below;
    // Whether a bridge end at (x, y, z) can be held at all (a pillar fits
    // under it); empty: always.
    std::function<bool(double x, double y, double z)> end_stands;
    // The disc touches the model on the first layer above z (the layer a
    // support point's tip holds); empty: always.
    std::function<bool(double z, double x, double y, double r)> touches_above;
    // A bar at height z would be trapped in a hollow of the model (plan/
    // cavities); empty: never.
    std::function<bool(double z, double x0, double y0, double x1, double y1)> bar_trapped;
    // The part of bar_trapped that is cheap and safe on any thread (bars an
    // earlier plan could not hold): the search leaves such bars out itself
    // instead of offering them one at a time. Empty: none.
    std::function<bool(double z, double x0, double y0, double x1, double y1)> bar_forbidden;
    // Whether bar_forbidden may hold for some bar at height z within the box
    // (false: for none; asked once per height of a seed, not per span).
    // Empty: as though true.
    std::function<bool(double z, double x_lo, double y_lo, double x_hi, double y_hi)> forbidden_near;

    // Largest layer top <= z (z itself without layers); < 0 when none.
    double snap_down(double z) const;
    // Tops of the layers whose top lies in (z_lo, z_hi], ascending.
    std::vector<double> tops_between(double z_lo, double z_hi, double layer_height) const;
};

// A point the planner still has to hold: a support point, or the end of a
// placed bridge that a lower bridge or a pillar must carry.
struct Active {
    double x = 0, y = 0;
    double z = 0;   // where its support reaches up to (a connector's or pillar's top)
    int point = -1; // support point index, or -1 for a bridge end
    // A bridge end: the top of what stands on its bar, and the compliance
    // (mm/N) of the connectors between, for METHOD's Standing rule.
    double hold = 0, give = 0;
};

// METHOD's Standing rule as the planner holds a connector to it: a
// kConnectorRadius stick from the top of a bar at bar_z up to a.z (however
// it leans), over the bar's own two layers (bar_inertia for its length),
// gives this much (mm/N) at the top of what stands on a (a.hold, or a.z);
// with what stands on a (a.give) it may give at most
// connector_allowance, half of what the whole may (the pillar under the
// bar takes the rest). Only for a.z above the bar's top. The rule off: 0.
double connector_compliance(const Active& a, double bar_z, double bar_length, const Settings& settings);
double connector_allowance(const Settings& settings);

// The lowest bar that may carry a (0: any): the lowest whose connector to a
// stays within connector_allowance, on the longest bar allowed. A bar lower down is no bar for a: its
// connector would be turned down when the bar is offered (a plate's bunny
// copy: 3056 bars offered and turned down so, each a search again).
double lowest_carrying_bar(const Active& a, const Settings& settings);

// One candidate bridge at height z (bottom of the bar) between (x0,y0) and
// (x1,y1), with the active points it would carry (ids in BridgeSearch).
struct Candidate {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0, z = 0;
    std::vector<int> carried;  // ascending
    double gain = 0, score = 0, l_max = 0;
    int seed = -1;             // which (point, direction) found it
    int end0 = -1, end1 = -1;  // the active points whose anchoring segments give the ends
};

// A bar or a bridge end by its coordinates in microns (a bar from either
// end is the same bar).
using BarKey = std::tuple<long, long, long, long, long>;
struct BarKeyHash {
    std::size_t operator()(const BarKey& k) const {
        // std::hash<long> is the identity, and nearby coordinates would
        // crowd the same slots: the five folded by multiplication, then one
        // murmur3 finaliser to spread the low bits (the probe uses them).
        // Called on every span a seed scans: one finaliser, not five.
        constexpr std::uint64_t kMul = 0x9e3779b97f4a7c15ULL;
        std::uint64_t h = static_cast<std::uint64_t>(std::get<0>(k));
        h = h * kMul + static_cast<std::uint64_t>(std::get<1>(k));
        h = h * kMul + static_cast<std::uint64_t>(std::get<2>(k));
        h = h * kMul + static_cast<std::uint64_t>(std::get<3>(k));
        h = h * kMul + static_cast<std::uint64_t>(std::get<4>(k));
        h = (h ^ (h >> 33)) * 0xff51afd7ed558ccdULL;
        h = (h ^ (h >> 33)) * 0xc4ceb9fe1a85ec53ULL;
        return static_cast<std::size_t>(h ^ (h >> 33));
    }
};

// A set or map keyed by BarKey: open addressing, linear probing, a power of
// two slots kept at most half full, keys packed to 32 bits a coordinate
// (microns: 2 km either way; a key beyond goes to a side map). Looked up
// far more often than filled (every span a seed scans), where
// std::unordered_map's node per entry cost two or three cache misses a
// lookup: on a plate of copies the tables outgrow the caches. Looked up
// only, never iterated.
template <typename V>
class BarTable {
public:
    // The value stored for k, or null.
    const V* find(const BarKey& k) const {
        Packed p;
        if (!pack(k, p)) {
            auto it = wide_.find(k);
            return it == wide_.end() ? nullptr : &it->second;
        }
        if (slots_.empty()) return nullptr;
        const std::size_t h = BarKeyHash{}(k);
        for (std::size_t i = h & mask_;; i = (i + 1) & mask_) {
            const Slot& sl = slots_[i];
            if (!sl.used) return nullptr;
            if (sl.hash == static_cast<std::uint32_t>(h) && sl.key == p) return &sl.value;
        }
    }
    bool contains(const BarKey& k) const { return find(k) != nullptr; }
    // Stores v for k unless k is already there (as emplace).
    void insert(const BarKey& k, V v) {
        Packed p;
        if (!pack(k, p)) {
            wide_.emplace(k, v);
            return;
        }
        if (2 * (size_ + 1) > slots_.size()) grow();
        place(BarKeyHash{}(k), p, v);
    }
    bool empty() const { return size_ == 0 && wide_.empty(); }

private:
    using Packed = std::array<std::int32_t, 5>;
    static bool pack(const BarKey& k, Packed& p) {
        const std::array<long, 5> v{std::get<0>(k), std::get<1>(k), std::get<2>(k), std::get<3>(k), std::get<4>(k)};
        for (std::size_t i = 0; i < 5; ++i) {
            if (v[i] < std::numeric_limits<std::int32_t>::min() || v[i] > std::numeric_limits<std::int32_t>::max())
                return false;
            p[i] = static_cast<std::int32_t>(v[i]);
        }
        return true;
    }
    struct Slot {
        Packed key{};
        std::uint32_t hash = 0;  // the low bits of the key's hash: where it goes when the table grows
        V value{};
        bool used = false;
    };
    void place(std::size_t h, const Packed& p, V v) {
        for (std::size_t i = h & mask_;; i = (i + 1) & mask_) {
            Slot& sl = slots_[i];
            if (sl.used && sl.key == p) return;
            if (!sl.used) {
                sl = {p, static_cast<std::uint32_t>(h), v, true};
                ++size_;
                return;
            }
        }
    }
    void grow() {
        std::vector<Slot> old = std::move(slots_);
        slots_.assign(old.empty() ? 64 : 2 * old.size(), Slot{});
        mask_ = slots_.size() - 1;
        size_ = 0;
        for (const Slot& sl : old)
            if (sl.used) place(sl.hash, sl.key, sl.value);
    }
    std::vector<Slot> slots_;
    std::size_t mask_ = 0, size_ = 0;
    std::unordered_map<BarKey, V, BarKeyHash> wide_;
};

// The model's answers about bars and bridge ends, which depend on the model
// and the settings only: a search made again on the same model (the
// pipeline plans again without bars it could not hold as built) reuses them
// instead of asking again (bunny.prusaslicer25: 516k pillar descents over
// four plans, 130k of them distinct). Looked up only, never iterated.
class BarEndAnswers;  // plan/pillars.hpp
class LeanInAnswers;  // plan/lean_in.hpp
class DescentCache;   // plan/pillars.hpp
struct ModelAnswers {
    BarTable<bool> bars;  // bar_clear
    BarTable<bool> ends;  // end_stands
    // What the pillar searches under bridge ends found, for the model view's
    // end_stands (set by plan_scaffold).
    std::shared_ptr<BarEndAnswers> bar_ends;
    // The lean-ins weak pillars are compared with (set by plan_scaffold).
    std::shared_ptr<LeanInAnswers> lean_ins;
    // The pillars' walks down (set by plan_scaffold).
    std::shared_ptr<DescentCache> descents;
};

// The set of active points with, for each point and sweep direction, the
// best bridge on the sweep line through it whose span contains the point.
//
// Cost. Let D = sweep directions, N = active points and K the points in a
// 60 x 10 mm window (the reach of a bridge: 30 mm either way along the sweep
// line, 5 mm across; set by the point density, not by N). One seed (point,
// direction) costs an rtree query, O(log N + K), plus its search, O(H K^2)
// with H <= K candidate heights (pruned by score bounds in practice).
// Building all seeds is O(D N (log N + K^3)). A greedy step changes the
// points one bridge carries and its two ends, all within 5 mm of the bar, so
// it recomputes only the O(D K) seeds whose window holds one of them:
// O(D K^4) per step, at most N steps, O(D N K^4 + N log N) in all: linear in
// N at a fixed density, steeply growing with the density. Measured
// (tools/bench_plan.cpp, no model): 0.11, 0.21, 0.27 ms per point for 100,
// 1k, 10k points at 1000 points per 200 x 200 mm; 7.6 ms per point for 10k
// points crowded into 200 x 200 mm (K ~ 150).
//
// Threads. The seeds made dirty by one step are recomputed on up to
// `threads` threads (0: the machine's cores, at most kMaxPlanThreads): a
// seed's result depends only on the active set and on the model's answers,
// which are pure (their caches and the model's own are behind one lock),
// and the ranking is updated afterwards in seed order, so the plan is the
// same for any thread count. With `helpers` (a model view per thread
// after the first, each over caches of its own: Obstacles::another), the
// threads ask the model at once and only the shared answers are locked.
inline constexpr int kMaxPlanThreads = 4;
class BridgeSearch {
public:
    // `answers`: shared with other searches on the same model and settings
    // (null: its own).
    BridgeSearch(const ModelView& model, const Settings& settings, int threads = 0,
                 std::shared_ptr<ModelAnswers> answers = nullptr, std::vector<const ModelView*> helpers = {});
    BridgeSearch(const BridgeSearch&) = delete;  // the rtree and buffers are its own
    BridgeSearch& operator=(const BridgeSearch&) = delete;
    // A copy of the search as it stands (its model's answers shared), asking
    // `model` from now on: a plan made again resumes from it.
    std::unique_ptr<BridgeSearch> clone(const ModelView& model, std::vector<const ModelView*> helpers = {}) const;

    int add(const Active& a);   // returns the point's id
    void remove(int id);
    const Active& active(int id) const { return points_[id]; }
    bool alive(int id) const { return alive_[id]; }
    int size() const { return static_cast<int>(points_.size()); }

    // The best-scoring candidate over all seeds whose bar is clear of the
    // model and which was not rejected; nullopt when no bridge has positive gain.
    std::optional<Candidate> best();
    // Marks for a search again the seeds that may offer a bar near or along
    // the bar (x0, y0) -> (x1, y1): a state kept by an earlier plan was
    // searched without the bars forbidden since (ModelView::bar_forbidden).
    void stale_near(double x0, double y0, double x1, double y1);
    // Recomputes the seeds a step left out of date, as best() does first: a
    // state kept for a plan made again is kept searched (a plan made again
    // starts where this one did, so its first search is not made twice).
    void refresh();
    // Never offer this bridge again (it failed a later check).
    void reject(const Candidate& c);
    // Whether a pillar can stand under a bridge end at (x, y, z): the model
    // view's test, asked once per end and remembered.
    bool end_stands(double x, double y, double z) { return end_stands(*model_, *scratch_[0], x, y, z); }
    // No connector reaches point `id` from c's bar: bars on the same line at
    // the same height no longer count it as carried. Without this a seed
    // offers the same failing bar again with each other pair of ends, one
    // rejection at a time (bunny.slic3r13 at --min-overhang-area 0: 15,636
    // rejections and 47 s).
    void no_connector(int id, const Candidate& c);

    // Seeds recomputed so far (for the benchmark).
    long long seed_evaluations() const { return evaluations_; }

private:
    struct Seed {
        bool dirty = false;  // queued in dirty_
        bool has = false;
        bool bar_checked = false;  // best's bar already tested against the model
        int blocked = 0;           // bars of this seed found blocked so far
        int ends_failed = 0;       // bests of this seed with a span whose end could not stand
        // Spans taken on the way to best without asking whether a pillar
        // stands under their ends (x0, y0, x1, y1, z); none: asked, or
        // asked along the way.
        std::vector<std::array<double, 5>> takes;
        Candidate best;
    };
    using Key = BarKey;
    static Key key_of(double x0, double y0, double x1, double y1, double z);

    void mark_around(double x, double y, double margin = 0);
    struct Scratch;                 // evaluate()'s buffers, one per thread
    void evaluate(int seed, Scratch& sc);
    void evaluate_all(const std::vector<int>& seeds);
    // The model's answers as asked through `mv` (the calling thread's view).
    bool bar_clear(const ModelView& mv, Scratch& sc, double x0, double y0, double x1, double y1, double z);
    bool end_stands(const ModelView& mv, Scratch& sc, double x, double y, double z);
    // The answer stored for `key`, or ask() stored (the model asked
    // outside the lock when each thread has a view of its own).
    template <class Ask>
    bool answer(BarTable<bool>& table, const Key& key, Ask ask);
    // The same, asked first of the answers this thread has seen (`seen`,
    // its Scratch's) when several threads share the table.
    template <class Ask>
    bool answer(BarTable<bool>& table, BarTable<bool>& seen, const Key& key, Ask ask);
    // Thread t's view of the model.
    const ModelView& model_of(int t) const { return t == 0 || helpers_.empty() ? *model_ : *helpers_[t - 1]; }

    BridgeSearch(const BridgeSearch& other, const ModelView& model, std::vector<const ModelView*> helpers);
    const ModelView* model_;
    std::vector<const ModelView*> helpers_;  // threads 1.. : views of their own (empty: all ask model_)
    const Settings& s_;
    double reach_ = 0;  // radius of the window's bounding circle
    std::vector<Active> points_;
    std::vector<double> low_;       // per point id: lowest_carrying_bar
    std::vector<char> alive_;
    std::vector<Seed> seeds_;       // id * D + direction
    std::vector<int> dirty_;        // seeds to recompute before the next best()
    std::set<std::pair<double, int>> ranked_;  // (-score, seed): best first, ties by seed
    // Looked up only, never iterated: hashing keeps the plan deterministic.
    BarTable<char> rejected_;
    // The lines (direction, offset to kRejectLineTol) and heights of the
    // rejected bars, hashed to a bit each: a seed asks the table about its
    // spans only at a height where its line may hold one (most spans were
    // looked up for nothing: a fifth of a plate's time). A bit set by another
    // line only costs the lookups.
    std::vector<std::uint64_t> rejected_lines_;
    void mark_rejected(double x0, double y0, double x1, double y1, double z);
    bool line_may_hold_rejected(int direction, double v, double z) const;
    std::shared_ptr<ModelAnswers> answers_;
    struct Miss {
        int direction;
        double v, z;  // the line's offset across its direction, the bar's height
    };
    std::vector<std::vector<Miss>> misses_;  // per point id
    long long evaluations_ = 0;
    struct Index;                   // the rtree over alive points
    std::shared_ptr<Index> index_;
    std::vector<std::shared_ptr<Scratch>> scratch_;  // per thread
    int threads_ = 1;
    std::mutex model_mutex_;        // the caches below and the model's own (Obstacles fills rasters lazily)
    // Held while asking the model, when seeds are evaluated on more than one
    // thread (on one, nobody else asks: no lock to take).
    std::unique_lock<std::mutex> model_lock() {
        return threads_ > 1 ? std::unique_lock<std::mutex>(model_mutex_) : std::unique_lock<std::mutex>();
    }
};

}  // namespace scaffold::plan
