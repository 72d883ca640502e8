#include "toolpath/support_paths.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numbers>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

// Boost.Geometry's rescaling trips GCC's maybe-uninitialized analysis.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#pragma GCC diagnostic pop

#include "plan/braces.hpp"
#include "plan/pillars.hpp"
#include "toolpath/bar_check.hpp"

namespace scaffold::toolpath {

std::vector<Point> loop(double cx, double cy, double r, double width) {
    const std::vector<std::array<double, 2>> vertices = plan::loop_vertices(cx, cy, r, width);
    std::vector<Point> pts;
    pts.reserve(vertices.size());
    for (const auto& v : vertices) pts.push_back({v[0], v[1]});
    return pts;
}

namespace {

constexpr double kZEps = 1e-6;

// A loop whose centre line stays within this many bead widths of one
// already printed on the layer retraces it.
constexpr double kRetrace = 0.2;

struct Square {
    double x, y, half;
    bool overlaps(const Square& o) const { return std::abs(x - o.x) < half + o.half && std::abs(y - o.y) < half + o.half; }
    bool contains(const Square& o) const { return std::abs(x - o.x) + o.half <= half && std::abs(y - o.y) + o.half <= half; }
};

struct Ring {
    double x, y, rc;  // centre and centre-line radius
};

// The air between a loop of centre-line radius rc around (x, y) and the
// ring `o` around it, bead edge to bead edge (beads w wide): negative where
// the loop is not wholly inside.
double room_inside(const Ring& o, double x, double y, double rc, double w) {
    return o.rc - std::hypot(x - o.x, y - o.y) - rc - w;
}

// A column's loop of outer radius r around (cx, cy) and, for a wide column
// not sized for METHOD's Standing rule, a second wall inside it (for the
// same stiffness a wider single wall costs less): outer first.
std::vector<Path> column_loops(const plan::Column& c, double cx, double cy, double r, PathKind kind, double speed,
                               double width) {
    Path p;
    p.kind = kind;
    p.width = width;
    p.speed_mm_s = speed;
    p.points = loop(cx, cy, r, width);
    std::vector<Path> out{p};
    if (plan::second_wall(c, r, width)) {
        p.points = loop(cx, cy, r - width * 0.9, width);
        out.push_back(std::move(p));
    }
    return out;
}

// Outline plus zigzag fill of a square of side `size` around (cx, cy).
Path raft(double cx, double cy, double size, double width, double speed) {
    Path p;
    p.kind = PathKind::Raft;
    p.width = width;
    p.speed_mm_s = speed;
    double h = size / 2 - width / 2;
    p.points = {{cx - h, cy - h}, {cx + h, cy - h}, {cx + h, cy + h}, {cx - h, cy + h}, {cx - h, cy - h}};
    bool left = true;
    for (double y = cy - h + width; y < cy + h - width * 0.5; y += width) {
        double x0 = cx - h + width, x1 = cx + h - width;
        p.points.push_back({left ? x0 : x1, y});
        p.points.push_back({left ? x1 : x0, y});
        left = !left;
    }
    return p;
}

namespace bg = boost::geometry;
using BgPoint = bg::model::d2::point_xy<double>;
using BgPolygon = bg::model::polygon<BgPoint>;
using BgMulti = bg::model::multi_polygon<BgPolygon>;

int find_root(std::vector<int>& parent, int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
}

// Loops on one layer whose centre lines cross (pillars standing closer than
// their diameter) are printed as the outline of their union, one path
// instead of two crossing ones: nothing is extruded twice, and the merged
// column is a hollow column of that outline on every layer it stays merged
// (what lies inside it is the filled footprint that holds the next layer).
// A loop inside another is left alone: the column above may stand on it.
// `loops` are the indices in `paths` of the single-wall loops, with their
// rings. A hole of the union is outlined only on the bed, or where the
// layer below (`below`, null if none) printed beads within `reach` of all
// its outline:
// where loops close round a hole that was inside the union below, its
// outline would stand over the hollow of that union, on nothing.
// Whether every vertex of `ring` lies within `reach` of a bead of `below`.
template <class R>
bool held_from(const std::vector<Path>* below, const R& ring, double reach) {
    if (!below) return false;
    for (const auto& v : ring) {
        bool near = false;
        for (const Path& p : *below) {
            for (std::size_t i = 1; i < p.points.size() && !near; ++i) {
                const Point &a = p.points[i - 1], &b = p.points[i];
                const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
                const double t = l2 > 0 ? std::clamp(((v.x() - a.x) * dx + (v.y() - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
                near = std::hypot(v.x() - a.x - dx * t, v.y() - a.y - dy * t) <= reach;
            }
            if (near) break;
        }
        if (!near) return false;
    }
    return true;
}

void merge_crossing_loops(std::vector<Path>& paths, const std::vector<std::pair<std::size_t, Ring>>& loops,
                          bool on_bed, const std::vector<Path>* below, double reach) {
    const int n = static_cast<int>(loops.size());
    if (n < 2) return;
    // A loop wholly inside another's is merged only with loops inside one
    // too: a union with the outer loop would fill it in, and the hollow
    // outer column holds nothing there for the inner one to stand on.
    std::vector<char> inner(n, 0);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n && !inner[a]; ++b) {
            const Ring &p = loops[a].second, &q = loops[b].second;
            inner[a] = b != a && q.rc > p.rc && std::hypot(p.x - q.x, p.y - q.y) + p.rc < q.rc - 1e-6;
        }
    std::vector<int> parent(n);
    for (int k = 0; k < n; ++k) parent[k] = k;
    bool any = false;
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b) {
            const Ring &p = loops[a].second, &q = loops[b].second;
            const double d = std::hypot(p.x - q.x, p.y - q.y);
            if (inner[a] == inner[b] && d < p.rc + q.rc - 1e-6 && d > std::abs(p.rc - q.rc) + 1e-6) {
                parent[find_root(parent, b)] = find_root(parent, a);
                any = true;
            }
        }
    if (!any) return;
    std::vector<std::vector<int>> groups(n);
    for (int k = 0; k < n; ++k) groups[find_root(parent, k)].push_back(k);
    std::vector<char> drop(paths.size(), 0);
    std::vector<Path> merged;
    for (const std::vector<int>& g : groups) {
        if (g.size() < 2) continue;
        BgMulti all;
        try {
            // Pairwise, in rounds (a balanced tree of unions): a group of
            // hundreds of loops (dense pillars) would otherwise make each
            // union as large as everything merged so far.
            std::vector<BgMulti> parts;
            for (int k : g) {
                BgPolygon poly;
                for (const Point& pt : paths[loops[k].first].points) poly.outer().push_back({pt.x, pt.y});
                bg::correct(poly);
                parts.push_back(BgMulti{poly});
            }
            while (parts.size() > 1) {
                std::vector<BgMulti> next((parts.size() + 1) / 2);
                for (std::size_t i = 0; i + 1 < parts.size(); i += 2) bg::union_(parts[i], parts[i + 1], next[i / 2]);
                if (parts.size() % 2) next.back() = std::move(parts.back());
                parts = std::move(next);
            }
            all = std::move(parts.front());
        } catch (const bg::exception&) {
            continue;  // a degenerate overlay: keep the loops as they are
        }
        if (all.empty()) continue;
        const Path& proto = paths[loops[g.front()].first];
        for (int k : g) drop[loops[k].first] = 1;
        for (const BgPolygon& poly : all) {
            auto add = [&](const auto& ring) {
                Path p = proto;
                p.points.clear();
                for (const BgPoint& pt : ring) p.points.push_back({pt.x(), pt.y()});
                if (p.points.size() >= 4) merged.push_back(std::move(p));
            };
            add(poly.outer());
            // A hole narrower than a bead is covered by the beads around it:
            // its outline would be a speck, moving from layer to layer with
            // the slanted loops that make it, over nothing.
            for (const auto& hole : poly.inners())
                if (std::abs(bg::area(hole)) >= proto.width * proto.width && (on_bed || held_from(below, hole, reach)))
                    add(hole);
        }
    }
    std::vector<Path> kept;
    for (std::size_t i = 0; i < paths.size(); ++i)
        if (!drop[i]) kept.push_back(std::move(paths[i]));
    for (Path& p : merged) kept.push_back(std::move(p));
    paths = std::move(kept);
}

// Whether a bead of `paths` comes within `reach` (centre line to centre
// line) of the point, or of the ring's centre line.
// (The first `count` paths.)
bool meets(const std::vector<Path>& paths, std::size_t count, double x, double y, double rc, double reach) {
    for (std::size_t j = 0; j < count; ++j) {
        const Path& p = paths[j];
        for (std::size_t i = 0; i < p.points.size(); ++i) {
            const Point& b = p.points[i];
            const Point& a = i > 0 ? p.points[i - 1] : b;
            const double near = layers::segment_distance(x, y, a.x, a.y, b.x, b.y);
            const double far = std::max(std::hypot(a.x - x, a.y - y), std::hypot(b.x - x, b.y - y));
            if (near <= rc + reach && far >= rc - reach) return true;
        }
    }
    return false;
}

// A column's loop that rests on nothing below, over the hollow of a wider
// loop (a branch on a trunk widened after it was placed; a tip's neck
// narrowing in one layer inside the piece it stands on), has no way down by
// METHOD's Standing rule: a floating island. Four short bridged spokes out
// to the wider loop (the nearest enclosing one on its own layer, else on
// the layer below, where the spokes' ends rest on it) make one island with
// a way down. Spokes whose outer end meets no bead (an arc merged away)
// are left out.
void spoke_inner_loops(std::vector<Path>& paths, const std::vector<Ring>& firsts, const std::vector<Ring>& rings,
                       const std::vector<Path>* below, const std::vector<Ring>* below_rings, double w, double speed,
                       double slack) {
    auto enclosing = [&](const Ring& in, const std::vector<Ring>& of) {
        const Ring* out = nullptr;
        for (const Ring& o : of) {
            if (room_inside(o, in.x, in.y, in.rc, w) > slack && (!out || o.rc < out->rc)) out = &o;
        }
        return out;
    };
    const std::size_t own = paths.size();  // this layer's beads, spokes aside
    for (const Ring& in : firsts) {
        if (below && meets(*below, below->size(), in.x, in.y, in.rc, w + slack)) continue;
        const Ring* out = enclosing(in, rings);
        const bool on_own = out != nullptr;
        if (!out && below && below_rings) out = enclosing(in, *below_rings);
        if (!out) continue;
        const double vx = in.x - out->x, vy = in.y - out->y, d = std::hypot(vx, vy);
        const double a0 = d > 1e-9 ? std::atan2(vy, vx) : 0.0;
        for (int k = 0; k < 4; ++k) {
            const double ux = std::cos(a0 + k * std::numbers::pi / 2), uy = std::sin(a0 + k * std::numbers::pi / 2);
            const double uv = ux * vx + uy * vy;
            const double t = -uv + std::sqrt(uv * uv - (d * d - out->rc * out->rc));
            const Point p0{in.x + ux * in.rc, in.y + uy * in.rc}, p1{in.x + ux * t, in.y + uy * t};
            if (on_own ? !meets(paths, own, p1.x, p1.y, 0, w / 2 + slack)
                       : !meets(*below, below->size(), p1.x, p1.y, 0, w / 2 + slack))
                continue;
            Path s;
            s.points = {p0, p1};
            s.width = w;
            s.speed_mm_s = speed;
            s.kind = PathKind::Bridge;
            s.bridge = true;
            paths.push_back(std::move(s));
        }
    }
}

}  // namespace

// Layers with this many paths (a plate's) are ordered with a grid of their starts.
constexpr std::size_t kGridOrderFrom = 64;

// Nearest-first order from the previous path's end; ties keep the input
// order. Measured between the places as the file will hold them (three
// decimals): loops on a grid (--method pillars) tie exactly, and their
// ends, from sin and cos, differ in the last bit between C libraries, so
// the raw distances broke the tie one way on Linux and the other on
// Windows (anchor.cura413). As indices into `paths`.
std::vector<std::size_t> printing_order(const std::vector<Path>& paths) {
    const std::size_t n = paths.size();
    std::vector<std::size_t> out;
    out.reserve(n);
    if (n < 3) {
        for (std::size_t i = 0; i < n; ++i) out.push_back(i);
        return out;
    }
    auto written = [](double v) { return std::round(v * 1000) / 1000; };
    std::vector<Point> start(n);
    for (std::size_t i = 0; i < n; ++i) start[i] = {written(paths[i].points.front().x), written(paths[i].points.front().y)};
    std::vector<bool> used(n, false);
    Point at = paths[0].points.front();
    // The nearest unused start, the lowest index among equals.
    std::size_t best = n;
    double best_d = 1e300;
    auto consider = [&](std::size_t i) {
        const double dx = start[i].x - written(at.x), dy = start[i].y - written(at.y), d = dx * dx + dy * dy;
        if (d < best_d || (d == best_d && i < best)) best_d = d, best = i;
    };
    if (n < kGridOrderFrom) {
        for (std::size_t k = 0; k < n; ++k) {
            best = n, best_d = 1e300;
            for (std::size_t i = 0; i < n; ++i)
                if (!used[i]) consider(i);
            used[best] = true;
            at = paths[best].points.back();
            out.push_back(best);
        }
        return out;
    }
    // Many paths (a plate's layer): the starts in a grid of about one a
    // cell, searched ring by ring around the last end until no unsearched
    // cell can hold a start as near (one R rings away lies at least (R - 1)
    // cells off): the same order as comparing all.
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Point& p : start) x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const double cell = std::max({(x1 - x0) / side, (y1 - y0) / side, 1e-3});
    const int nx = static_cast<int>((x1 - x0) / cell) + 1, ny = static_cast<int>((y1 - y0) / cell) + 1;
    auto col = [&](double x) { return std::clamp(static_cast<int>(std::floor((x - x0) / cell)), 0, nx - 1); };
    auto row = [&](double y) { return std::clamp(static_cast<int>(std::floor((y - y0) / cell)), 0, ny - 1); };
    std::vector<std::vector<std::size_t>> cells(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
    for (std::size_t i = 0; i < n; ++i) cells[static_cast<std::size_t>(row(start[i].y)) * nx + col(start[i].x)].push_back(i);
    for (std::size_t k = 0; k < n; ++k) {
        best = n, best_d = 1e300;
        const int ci = col(written(at.x)), cj = row(written(at.y));
        for (int r = 0;; ++r) {
            if (best < n && best_d < std::pow(std::max(0, r - 1) * cell, 2)) break;
            if (r > nx + ny) break;
            for (int j = cj - r; j <= cj + r; ++j) {
                if (j < 0 || j >= ny) continue;
                const bool edge_row = j == cj - r || j == cj + r;
                for (int i = ci - r; i <= ci + r; i += edge_row ? 1 : 2 * r) {
                    if (i >= 0 && i < nx)
                        for (std::size_t q : cells[static_cast<std::size_t>(j) * nx + i])
                            if (!used[q]) consider(q);
                    if (r == 0) break;
                }
            }
        }
        used[best] = true;
        at = paths[best].points.back();
        out.push_back(best);
    }
    return out;
}

namespace {

// `paths` put in that order.
void order_paths(std::vector<Path>& paths) {
    const std::vector<std::size_t> order = printing_order(paths);
    std::vector<Path> out;
    out.reserve(paths.size());
    for (std::size_t i : order) out.push_back(std::move(paths[i]));
    paths = std::move(out);
}

// A bar passing beside a column it does not rest on, its line within the
// reach of the column's loop beneath but along the loop's edge, is held
// there by a sliver it only grazes: METHOD's rule (b) then judges each part
// of the bar from a held end left along the edge, not across it. A spur on
// the layer under the bar, straight out from the loop and under both bar
// lines, gives the bar a held stretch it crosses at right angles instead.
// The spur itself is a dangling end of the loop (under 1 mm past its reach).
// `held`: whether a spur would be held where it is printed (a spur whose far
// end comes within reach of other support beneath is no dangling end but a
// run between held ends, which rule (b) holds only across a gap: the
// shuttle at --min-overhang-area 0, a spur from a widened loop, 0.29 mm^2).
void add_spurs(std::vector<Path>& paths, const std::vector<plan::Bridge>& bridges, double z,
               const layers::Layer& bar_layer, const Settings& s,
               const std::function<bool(const Point&, const Point&)>& held) {
    constexpr double kRoundLoop = 0.01;  // mm: a loop's vertices all this close to one circle
    const double w = s.support_width;
    const double reach = bar_layer.height * std::tan(s.overhang_angle_deg * std::numbers::pi / 180) + s.resolution / 2;
    const std::size_t n_loops = paths.size();
    for (const plan::Bridge& br : bridges) {
        // This layer is the one right under the bar's first layer.
        if (!(z <= br.z + kZEps && bar_layer.z > br.z + kZEps)) continue;
        const double dx = br.x1 - br.x0, dy = br.y1 - br.y0, len = std::hypot(dx, dy);
        if (len < 1e-6) continue;
        const double ux = dx / len, uy = dy / len, ext = s.pillar_radius * 0.5;
        for (std::size_t i = 0; i < n_loops; ++i) {
            const Path& p = paths[i];
            if (p.kind == PathKind::Bridge || p.kind == PathKind::Raft || p.points.size() < 4) continue;
            const Point& f = p.points.front();
            const Point& b = p.points.back();
            if (std::hypot(f.x - b.x, f.y - b.y) > 1e-6) continue;  // not a loop
            double cx = 0, cy = 0;
            for (std::size_t k = 0; k + 1 < p.points.size(); ++k) cx += p.points[k].x, cy += p.points[k].y;
            cx /= static_cast<double>(p.points.size() - 1);
            cy /= static_cast<double>(p.points.size() - 1);
            double rc = 0, rmin = 1e300;
            for (const Point& q : p.points) {
                rc = std::max(rc, std::hypot(q.x - cx, q.y - cy));
                rmin = std::min(rmin, std::hypot(q.x - cx, q.y - cy));
            }
            // Only a column's own round loop: the outline of crossing loops
            // merged into one is no circle about its vertices' mean, and a
            // spur from that mean's circle stood off it, on nothing.
            if (rc - rmin > kRoundLoop) continue;
            const double outer = rc + p.width / 2;
            // Where the loop's centre falls along the bar, and how far aside.
            const double t = (cx - br.x0) * ux + (cy - br.y0) * uy;
            if (t < -ext || t > len + ext) continue;
            const double e = (cx - br.x0) * -uy + (cy - br.y0) * ux;  // signed, left of the bar positive
            const double near = std::abs(e) - w / 2, far = std::abs(e) + w / 2;
            auto grazes = [&](double d) { return d > outer * 0.85 && d < outer + reach + 0.15; };
            if (!grazes(near) && !grazes(far)) continue;
            // From the loop's centre line toward the bar, past its far line.
            const double sign = e > 0 ? -1.0 : 1.0;
            const double nx = sign * -uy, ny = sign * ux;
            const double from = rc, to = far + 0.3;
            if (to - from > 1.4 || to <= from) continue;
            Path spur;
            spur.kind = PathKind::Pillar;
            spur.width = w;
            spur.speed_mm_s = p.speed_mm_s;
            spur.points = {{cx + nx * from, cy + ny * from}, {cx + nx * to, cy + ny * to}};
            if (held(spur.points.front(), spur.points.back())) paths.push_back(std::move(spur));
        }
    }
}

// What each column has printed so far, for its bonds. Columns are pieces
// stacked on one another (Base::Column on the piece whose top is its
// bottom); branches may stand on one piece. A piece's loop is bonded when
// the gap down to the highest loop printed so far by it or the pieces
// under it (or to what the lowest stands on) is wider than the bond gap.
class Printed {
public:
    explicit Printed(const std::vector<plan::Column>& columns)
        : columns_(columns), below_(columns.size()), top_(columns.size(), -1.0) {
        std::map<std::tuple<double, double, double>, std::size_t> tops;
        for (std::size_t i = 0; i < columns.size(); ++i)
            tops.emplace(std::tuple{columns[i].x1, columns[i].y1, columns[i].z1}, i);
        for (std::size_t i = 0; i < columns.size(); ++i) {
            const plan::Column& c = columns[i];
            const auto it = c.base == plan::Base::Column ? tops.find({c.x0, c.y0, c.z0}) : tops.end();
            below_[i] = it != tops.end() && it->second != i ? it->second : i;
        }
    }

    // The height piece i's loop at z stands on: its own last loop, else
    // the nearest piece under it that printed one, else the bottom's base.
    double beneath(std::size_t i) const {
        if (top_[i] >= 0) return top_[i];
        std::size_t r = i;
        for (std::size_t steps = 0; below_[r] != r && steps < columns_.size(); ++steps) {
            r = below_[r];
            if (top_[r] >= 0) return top_[r];
        }
        return columns_[r].base == plan::Base::Bed ? 0.0 : columns_[r].z0;
    }

    void print(std::size_t i, double z) { top_[i] = std::max(top_[i], z); }

private:
    const std::vector<plan::Column>& columns_;
    std::vector<std::size_t> below_;  // the piece it stands on, or itself
    std::vector<double> top_;         // its highest loop printed, -1 for none
};

// A column's loop on a layer far above the last it was printed on (or
// what it stands on), where a bond goes under it.
struct Bonded {
    double z0 = 0;  // the height it was printed up to, or stands on
    double z1 = 0;  // its loop's height
    Path path;
    bool single = false;  // a single wall, merged with the loops it crosses
    Ring ring;
};

// The loops to bond under the lowest of `heights` (none given: none):
// columns reaching one of them over a gap wider than `gap` and at most
// `most` from what they were printed up to (Printed::beneath). Each is
// noted printed there, so the pieces on it see no gap.
std::vector<Bonded> bonds_under(const std::vector<plan::Column>& columns, const std::vector<std::size_t>& by_base,
                                const std::vector<double>& heights, double gap, double most, const Settings& s,
                                Printed& printed) {
    std::vector<Bonded> out;
    if (heights.empty()) return out;
    const double w = s.support_width;
    std::vector<Ring> rings;
    for (std::size_t ci : by_base) {
        const plan::Column& c = columns[ci];
        double z = 1e300;  // the lowest of the heights it reaches
        for (double h : heights)
            if (h > c.z0 + kZEps && h <= c.z1 + kZEps) z = std::min(z, h);
        if (z == 1e300) continue;
        const double on = printed.beneath(ci);
        if (!(on > 0) || z - on <= gap + kZEps || z - on > most + kZEps) continue;
        printed.print(ci, z);
        double cx, cy;
        plan::column_centre_at(c, z, cx, cy);
        const double r = plan::column_radius_at(c, z, s), rc = plan::loop_shape(r, w).centre_radius;
        if (std::any_of(rings.begin(), rings.end(),
                        [&](const Ring& o) { return plan::loops_apart(o.x, o.y, o.rc, cx, cy, rc) <= kRetrace * w; }))
            continue;
        rings.push_back({cx, cy, rc});
        std::vector<Path> loops = column_loops(c, cx, cy, r, c.x0 != c.x1 || c.y0 != c.y1 ? PathKind::Connector : PathKind::Pillar,
                                               s.support_speed_mm_s, w);
        if (loops.size() > 1) out.push_back({on, z, std::move(loops[1]), false, rings.back()});  // the inner wall first
        out.push_back({on, z, std::move(loops[0]), loops.size() == 1, rings.back()});
    }
    return out;
}

// The bond layers under layer `l`: one halfway through each gap (from
// what the loops were printed up to, to their height; the gap is at most
// kBondMostLayers, so each half at most kBondGapLayers), in the order of
// their heights. Crossing loops are merged as on the layer (they stand on
// solid support: holes kept).
template <class Finish>
void add_bonds(std::vector<Bonded>& bonded, int l, const Finish& finish, std::vector<LayerPaths>& out) {
    auto mid = [](const Bonded& b) { return (b.z0 + b.z1) / 2; };
    std::stable_sort(bonded.begin(), bonded.end(), [&](const Bonded& a, const Bonded& b) { return mid(a) < mid(b); });
    for (std::size_t i = 0; i < bonded.size();) {
        std::size_t j = i;
        while (j < bonded.size() && mid(bonded[j]) <= mid(bonded[i]) + kZEps) ++j;
        LayerPaths b;
        b.layer = l;
        b.bond_height = (bonded[i].z1 - bonded[i].z0) / 2;
        b.bond_z = mid(bonded[i]);
        std::vector<std::pair<std::size_t, Ring>> singles;
        for (std::size_t m = i; m < j; ++m) {
            if (bonded[m].single) singles.push_back({b.paths.size(), bonded[m].ring});
            b.paths.push_back(bonded[m].path);
        }
        merge_crossing_loops(b.paths, singles, true, nullptr, 0);
        finish(b);
        out.push_back(std::move(b));
        i = j;
    }
}

}  // namespace

SupportPaths make_paths(const plan::Scaffold& scaffold, const layers::LayerStack& stack, const Settings& s,
                        const plan::Obstacles* obstacles) {
    if (!obstacles) return make_paths(scaffold, stack, s, TravelClear{});
    return make_paths(scaffold, stack, s, [obstacles](int layer, const Point& a, const Point& b, double width) {
        return obstacles->segment_clear(layer, a.x, a.y, b.x, b.y, width);
    });
}

SupportPaths make_paths(const plan::Scaffold& scaffold, const layers::LayerStack& stack, const Settings& s,
                        const TravelClear& clear) {
    SupportPaths out;
    const double w = s.support_width;
    // The layer printed next above each layer (-1 for the top).
    std::vector<int> next(stack.layers.size(), -1);
    for (int l = 0; l < static_cast<int>(stack.layers.size()); ++l)
        for (int k = l + 1; k < static_cast<int>(stack.layers.size()); ++k)
            if (!stack.layers[k].purge && stack.layers[k].z > stack.layers[l].z + kZEps) {
                next[l] = k;
                break;
            }
    std::vector<int> printed_at(stack.layers.size(), -1);  // index in out.layers
    Printed printed(scaffold.columns);
    // Columns by their bottoms, lowest first: a piece's bond is decided
    // before those of the pieces standing on it.
    std::vector<std::size_t> by_base(scaffold.columns.size());
    for (std::size_t i = 0; i < by_base.size(); ++i) by_base[i] = i;
    std::stable_sort(by_base.begin(), by_base.end(),
                     [&](std::size_t a, std::size_t b) { return scaffold.columns[a].z0 < scaffold.columns[b].z0; });
    double printed_up_to = 0;  // the highest layer so far
    struct Looped {
        double z = -1, x = 0, y = 0, rc = 0;
    };
    std::vector<Looped> looped_at(scaffold.columns.size());  // each column's last loop
    std::vector<std::vector<Ring>> rings_at(stack.layers.size());  // each layer's loops' rings
    for (int l = 0; l < static_cast<int>(stack.layers.size()); ++l) {
        const layers::Layer& layer = stack.layers[l];
        if (layer.purge) continue;
        double z = layer.z;
        // Cura prints the model's second layer over a raft a little under
        // its first (0.02 mm at 0.2 mm layers): such a layer gets its loops
        // as any other, but bonds go in only before the first of the group,
        // under the lowest of `heights` (the layer's own and those printed
        // right after it and under it, within two nominal layers), never
        // under what was printed already.
        const bool lower = z < printed_up_to - kZEps;
        printed_up_to = std::max(printed_up_to, z);
        std::vector<double> heights;
        if (!lower) {
            heights.push_back(z);
            for (int k = l + 1; k < static_cast<int>(stack.layers.size()); ++k) {
                const layers::Layer& after = stack.layers[k];
                if (after.purge) continue;
                if (after.z >= z - kZEps || after.z < z - 2 * s.layer_height) break;
                heights.push_back(after.z);
            }
        }
        bool first_layer = layer.on_bed;
        double speed = first_layer ? s.first_layer_speed_mm_s : s.support_speed_mm_s;
        LayerPaths lp;
        lp.layer = l;
        // What this layer already prints, so nothing is extruded twice: a
        // loop that (nearly) retraces one already printed is left out (the
        // column above rests on that one), a raft overlapping an earlier raft
        // too, and on the first layer the raft replaces the loop on it.
        std::vector<Square> rafts;
        std::vector<Ring> rings;
        std::vector<std::pair<std::size_t, Ring>> single_loops;  // path index, ring
        std::vector<Ring> firsts;  // loops that may not rest on their column's loop below
        const double h_nom = std::max(s.layer_height, layer.nominal_height);
        std::vector<Bonded> bonded =
            stack.z_varies ? std::vector<Bonded>{}
                           : bonds_under(scaffold.columns, by_base, heights, kBondGapLayers * h_nom,
                                         kBondMostLayers * h_nom, s, printed);
        // Widest loops first: of two loops nearly one (left out below), the
        // wider is printed, the stiffer column it stands for. Not on the
        // first layer, where rafts and feet are laid out in the plan's order.
        std::vector<std::pair<double, std::size_t>> here;
        for (std::size_t ci = 0; ci < scaffold.columns.size(); ++ci) {
            const plan::Column& c = scaffold.columns[ci];
            if (z <= c.z0 + kZEps || z > c.z1 + kZEps) continue;
            here.emplace_back(-plan::column_radius_at(c, z, s), ci);
        }
        if (!first_layer)
            std::stable_sort(here.begin(), here.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& [neg_r, ci] : here) {
            const plan::Column& c = scaffold.columns[ci];
            const double r = -neg_r;
            printed.print(ci, z);
            // A column whose base is on the bed starts on the first layer.
            double cx, cy;
            plan::column_centre_at(c, z, cx, cy);
            if (first_layer && c.base == plan::Base::Bed && c.raft_size > 0) {
                Square sq{cx, cy, c.raft_size / 2};
                bool overlaps = std::any_of(rafts.begin(), rafts.end(), [&](const Square& o) { return o.overlaps(sq); });
                if (!overlaps) {
                    lp.paths.push_back(raft(cx, cy, c.raft_size, w, speed));
                    rafts.push_back(sq);
                }
            }
            // A loop wholly on a raft of this layer is printed by the raft.
            if (first_layer && std::any_of(rafts.begin(), rafts.end(), [&](const Square& o) { return o.contains({cx, cy, r}); }))
                continue;
            const double rc = plan::loop_shape(r, w).centre_radius;
            auto apart = [](const Ring& o, double x, double y, double rc_) { return plan::loops_apart(o.x, o.y, o.rc, x, y, rc_); };
            if (std::any_of(rings.begin(), rings.end(), [&](const Ring& o) { return apart(o, cx, cy, rc) <= kRetrace * w; }))
                continue;
            // A loop mostly on top of one already printed on this layer is
            // left out where that one also holds this column's next loop (its
            // centre line within the reach of the printed bead): pillars
            // standing closer than their diameter then print one loop, not
            // two crossing ones. Never a column's top two layers (its tip).
            if (next[l] >= 0) {
                const double z2 = stack.layers[next[l]].z, h2 = stack.layers[next[l]].height;
                // The column's next loop: on this piece, or on the piece
                // stacked on it where this one ends here.
                const plan::Column* up = c.z1 > z2 + kZEps ? &c : nullptr;
                if (!up && c.top == plan::Top::Column && ci + 1 < scaffold.columns.size() &&
                    plan::stacked_on_previous(scaffold, static_cast<int>(ci + 1)) &&
                    scaffold.columns[ci + 1].z1 > z2 + kZEps)
                    up = &scaffold.columns[ci + 1];
                double cx2 = 0, cy2 = 0, rc2 = 0;
                if (up) {
                    plan::column_centre_at(*up, z2, cx2, cy2);
                    rc2 = plan::loop_shape(plan::column_radius_at(*up, z2, s), w).centre_radius;
                }
                const double hold = plan::loop_shift_limit(h2, s);
                if (up == &c && c.z1 > z2 + h2 + kZEps &&
                    std::any_of(rings.begin(), rings.end(), [&](const Ring& o) {
                        return apart(o, cx, cy, rc) <= hold && apart(o, cx2, cy2, rc2) <= hold;
                    }))
                    continue;
                // Or wholly inside a wider loop, beads apart, on this layer
                // and the next: a narrower column on a wider one's way down
                // (a bar end's pillar following a trunk) would stand there
                // as an island of its own with its own thin way down (bull
                // at --min-stiffness 10: 5.0 N/mm inside a 2 mm trunk). The
                // wider one carries it; where it leaves, its first loop is
                // spoked to it (spoke_inner_loops). Not in its tip.
                if (up && (up->top == plan::Top::Column || up->z1 > z2 + h2 + kZEps) &&
                    std::any_of(rings.begin(), rings.end(), [&](const Ring& o) {
                        return room_inside(o, cx, cy, rc, w) >= 0 && room_inside(o, cx2, cy2, rc2, w) >= 0;
                    }))
                    continue;
            }
            rings.push_back({cx, cy, rc});
            // Its first loop on support, the first after loops left out
            // (another's loop held it: on a column from the bed or the
            // model too, left out from its start), or one much narrower than
            // its own below (a tip's neck begins): its own loop below may not
            // hold it.
            const double z_below = layer.below >= 0 ? stack.layers[layer.below].z : -1.0;
            const bool left_out = z_below > c.z0 + kZEps && looped_at[ci].z < z_below - kZEps;
            const bool on_support = c.base != plan::Base::Model && c.base != plan::Base::Bed;
            if (layer.below >= 0 &&
                (left_out || (looped_at[ci].z < 0 && on_support) ||
                 (looped_at[ci].z >= 0 && std::hypot(cx - looped_at[ci].x, cy - looped_at[ci].y) +
                                                  std::abs(rc - looped_at[ci].rc) > w / 2)))
                firsts.push_back(rings.back());
            looped_at[ci] = {z, cx, cy, rc};
            const PathKind kind = (c.base == plan::Base::Bed && c.foot_radius > 0 && z < s.foot_height) ? PathKind::Foot
                                  : (c.x0 != c.x1 || c.y0 != c.y1)                                 ? PathKind::Connector
                                                                                                  : PathKind::Pillar;
            std::vector<Path> loops = column_loops(c, cx, cy, r, kind, speed, w);
            if (loops.size() == 1) single_loops.push_back({lp.paths.size(), rings.back()});
            for (Path& p : loops) lp.paths.push_back(std::move(p));
        }
        const int below = layer.below >= 0 ? printed_at[layer.below] : -1;
        merge_crossing_loops(lp.paths, single_loops, first_layer, below >= 0 ? &out.layers[below].paths : nullptr,
                             plan::loop_shift_limit(layer.height, s));
        spoke_inner_loops(lp.paths, firsts, rings, below >= 0 ? &out.layers[below].paths : nullptr,
                          layer.below >= 0 ? &rings_at[layer.below] : nullptr, w, s.bridge_speed_mm_s, s.resolution);
        rings_at[l] = std::move(rings);  // not asked again on this layer
        for (const plan::Bridge& br : scaffold.bridges) {
            // Two layers of two side-by-side lines: a 1 mm wide, 0.4 mm thick bar.
            if (z <= br.z + kZEps || z > br.z + kBridgeThickness + kZEps) continue;
            for (std::vector<Point>& line : bar_lines(br, w, s.pillar_radius)) {
                Path p;
                p.kind = PathKind::Bridge;
                p.bridge = true;
                p.width = w;
                p.speed_mm_s = s.bridge_speed_mm_s;
                p.points = std::move(line);
                lp.paths.push_back(std::move(p));
            }
        }
        if (next[l] >= 0)
            add_spurs(lp.paths, scaffold.bridges, z, stack.layers[next[l]], s, [&](const Point& a, const Point& b) {
                return segment_held(a, b, l, out.layers, stack, s);
            });
        if (lp.paths.empty() && bonded.empty()) continue;
        auto finish = [&](LayerPaths& e) {
            order_paths(e.paths);
            if (clear)
                for (std::size_t i = 1; i < e.paths.size(); ++i)
                    e.paths[i].retract =
                        !clear(l, e.paths[i - 1].points.back(), e.paths[i].points.front(), s.support_width);
        };
        add_bonds(bonded, l, finish, out.layers);
        if (lp.paths.empty()) continue;
        finish(lp);
        printed_at[l] = static_cast<int>(out.layers.size());
        out.layers.push_back(std::move(lp));
    }
    return out;
}

std::vector<std::vector<Point>> bar_lines(const plan::Bridge& br, double width, double pillar_radius) {
    const double dx = br.x1 - br.x0, dy = br.y1 - br.y0, len = std::hypot(dx, dy);
    if (len < 1e-6) return {};
    const double nx = -dy / len * width / 2, ny = dx / len * width / 2;
    // Reach into the pillar tops at both ends so the bar is anchored.
    const double ex = dx / len * pillar_radius * 0.5, ey = dy / len * pillar_radius * 0.5;
    std::vector<std::vector<Point>> out;
    for (int side : {-1, 1}) {
        Point a{br.x0 - ex + side * nx, br.y0 - ey + side * ny}, b{br.x1 + ex + side * nx, br.y1 + ey + side * ny};
        out.push_back(side < 0 ? std::vector<Point>{a, b} : std::vector<Point>{b, a});
    }
    return out;
}

std::vector<std::vector<std::size_t>> copy_clusters(const SupportPaths& one, const std::vector<Point>& offsets,
                                                    double apart) {
    // Where the copy's paths pass, over all layers: every bead sampled at
    // most kStep apart, each sample kept as the centre of its kCell square,
    // once. Every point of a bead's centre line lies within kStep / 2 + the
    // square's half diagonal of a centre kept.
    constexpr double kCell = 0.25, kStep = 0.25;
    const double slack = kStep / 2 + kCell * std::numbers::sqrt2 / 2;
    auto cell = [](double v, double size) { return static_cast<long>(std::floor(v / size)); };
    auto key = [](long i, long j) { return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint32_t>(j); };
    std::unordered_set<std::uint64_t> seen;
    std::vector<Point> centres;
    double widest = 0;
    for (const LayerPaths& lp : one.layers)
        for (const Path& p : lp.paths) {
            widest = std::max(widest, p.width);
            for (std::size_t k = 0; k < p.points.size(); ++k) {
                const Point& a = p.points[k];
                const Point& b = p.points[k + 1 < p.points.size() ? k + 1 : k];
                const int n = std::max(1, static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / kStep)));
                for (int t = 0; t <= n; ++t) {
                    const double x = a.x + (b.x - a.x) * t / n, y = a.y + (b.y - a.y) * t / n;
                    const long i = cell(x, kCell), j = cell(y, kCell);
                    if (seen.insert(key(i, j)).second)
                        centres.push_back({(static_cast<double>(i) + 0.5) * kCell, (static_cast<double>(j) + 0.5) * kCell});
                }
            }
        }
    // Two copies' beads (edges) at least `apart` mm apart: their centres
    // farther than `reach` from each other. Looked up in squares of that size.
    const double reach = apart + widest + 2 * slack;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_square;
    for (std::uint32_t k = 0; k < centres.size(); ++k)
        by_square[key(cell(centres[k].x, reach), cell(centres[k].y, reach))].push_back(k);
    auto meet = [&](double dx, double dy) {
        for (const Point& c : centres) {
            const double x = c.x + dx, y = c.y + dy;
            const long i = cell(x, reach), j = cell(y, reach);
            for (long di = -1; di <= 1; ++di)
                for (long dj = -1; dj <= 1; ++dj) {
                    auto it = by_square.find(key(i + di, j + dj));
                    if (it == by_square.end()) continue;
                    for (std::uint32_t k : it->second)
                        if (std::hypot(centres[k].x - x, centres[k].y - y) <= reach) return true;
                }
        }
        return false;
    };
    // Joined: each copy labelled with the lowest copy it reaches.
    std::vector<std::size_t> root(offsets.size());
    for (std::size_t a = 0; a < offsets.size(); ++a) root[a] = a;
    auto find = [&](std::size_t a) {
        while (root[a] != a) a = root[a] = root[root[a]];
        return a;
    };
    for (std::size_t a = 0; a < offsets.size(); ++a)
        for (std::size_t b = a + 1; b < offsets.size(); ++b)
            if (find(a) != find(b) && meet(offsets[b].x - offsets[a].x, offsets[b].y - offsets[a].y)) {
                const std::size_t ra = find(a), rb = find(b);
                root[std::max(ra, rb)] = std::min(ra, rb);
            }
    std::vector<std::vector<std::size_t>> out;
    std::vector<int> cluster_of(offsets.size(), -1);
    for (std::size_t a = 0; a < offsets.size(); ++a) {
        const std::size_t r = find(a);
        if (cluster_of[r] < 0) {
            cluster_of[r] = static_cast<int>(out.size());
            out.emplace_back();
        }
        out[static_cast<std::size_t>(cluster_of[r])].push_back(a);
    }
    return out;
}

SupportPaths placed_paths(const std::vector<PlacedPaths>& parts, const TravelClear& clear) {
    // Every part's entries by (layer, bond or not, bond height to the
    // micron): make_paths' order.
    using Entry = std::tuple<int, bool, long long>;
    auto entry_of = [](const LayerPaths& lp) {
        return Entry{lp.layer, !lp.bond(), lp.bond() ? std::llround(lp.bond_z * 1e6) : 0};
    };
    std::map<Entry, std::vector<std::pair<std::size_t, const LayerPaths*>>> entries;
    for (std::size_t k = 0; k < parts.size(); ++k)
        for (const LayerPaths& lp : parts[k].paths->layers) entries[entry_of(lp)].push_back({k, &lp});
    SupportPaths out;
    out.layers.reserve(entries.size());
    std::vector<Path> all;
    std::vector<std::pair<std::size_t, std::size_t>> from;  // each path's part and index in its part's entry
    std::map<std::tuple<const SupportPaths*, std::size_t, std::size_t>, bool> asked;  // within one part: retract
    for (const auto& [e, here] : entries) {
        LayerPaths& m = out.layers.emplace_back();
        m.layer = here.front().second->layer;
        m.bond_z = here.front().second->bond_z;
        m.bond_height = here.front().second->bond_height;
        all.clear();
        from.clear();
        for (const auto& [k, lp] : here) {
            const Point& o = parts[k].offset;
            for (std::size_t j = 0; j < lp->paths.size(); ++j) {
                Path& q = all.emplace_back(lp->paths[j]);
                for (Point& pt : q.points) {
                    pt.x += o.x;
                    pt.y += o.y;
                }
                from.push_back({k, j});
            }
        }
        // Nearest first over all parts, as make_paths orders a layer (part
        // after part, each from where its own order starts, travelled 17 %
        // more on elephant x4 and printed 8 min longer on bunny x8). A
        // travel its part made too (the next path of the same part) keeps
        // the part's answer; one between the same two paths of another part
        // moved alike (`clear` is asked where the plate is the same around
        // every part) is asked once.
        const std::vector<std::size_t> order = printing_order(all);
        m.paths.reserve(all.size());
        asked.clear();
        for (std::size_t i = 0; i < order.size(); ++i) {
            const auto [k, j] = from[order[i]];
            Path& p = m.paths.emplace_back(std::move(all[order[i]]));
            const auto [k0, j0] = i > 0 ? from[order[i - 1]] : std::pair<std::size_t, std::size_t>{};
            if (i == 0) {
                p.retract = true;
            } else if (k0 != k || j0 + 1 != j) {
                const Path& before = m.paths[i - 1];
                const auto key = std::make_tuple(parts[k].paths, j0, j);
                auto it = k0 == k ? asked.find(key) : asked.end();
                if (it == asked.end()) {
                    p.retract = !clear || !clear(m.layer, before.points.back(), p.points.front(), p.width);
                    if (k0 == k) asked.emplace(key, p.retract);
                } else {
                    p.retract = it->second;
                }
            }
        }
    }
    return out;
}

double paths_volume(const SupportPaths& paths, const layers::LayerStack& stack) {
    double v = 0;
    for (const LayerPaths& lp : paths.layers) {
        const double h = lp.bond() ? lp.bond_height : stack.layers[lp.layer].height;
        for (const Path& path : lp.paths)
            for (std::size_t i = 1; i < path.points.size(); ++i)
                v += std::hypot(path.points[i].x - path.points[i - 1].x, path.points[i].y - path.points[i - 1].y) * path.width * h;
    }
    return v;
}

void move_paths(SupportPaths& paths, double dx, double dy) {
    for (LayerPaths& lp : paths.layers)
        for (Path& path : lp.paths)
            for (Point& p : path.points) {
                p.x += dx;
                p.y += dy;
            }
}

}  // namespace scaffold::toolpath

