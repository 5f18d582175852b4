#include "analysis/crack_shape.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace frac::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Least squares x = a + s h over the points; NaN when fewer than 3.
struct Line {
  double a = kNaN, s = kNaN;
  std::size_t n = 0;
};
Line fit(const std::vector<std::array<double, 2>>& hx) {
  Line l;
  l.n = hx.size();
  if (l.n < 3) return l;
  double mh = 0, mx = 0;
  for (const auto& p : hx) {
    mh += p[0];
    mx += p[1];
  }
  mh /= static_cast<double>(l.n);
  mx /= static_cast<double>(l.n);
  double shh = 0, shx = 0;
  for (const auto& p : hx) {
    shh += (p[0] - mh) * (p[0] - mh);
    shx += (p[0] - mh) * (p[1] - mx);
  }
  if (!(shh > 0)) return l;
  l.s = shx / shh;
  l.a = mx - l.s * mh;
  return l;
}

// Angle of the line x = a + s h to the crack line (h across it, x along it), in degrees: 90 for a front
// straight across, below 90 for one that leans back from the crack line (a wedge opening behind the tip).
double angle_to_line(const Line& l) {
  return std::isnan(l.s) ? kNaN : std::atan2(1.0, -l.s) * 180.0 / std::numbers::pi;
}

// Broken bonds across the crack line (the tip: the farthest along it) and in the bulk, and the grip bonds
// (clamped rows to free rows) behind the tip, counted once the tip is known.
void count_broken_bonds(const mesh::NodeMesh& m, const io::BodyFrame& f, std::size_t clamp_rows, CrackShape& s) {
  const std::size_t nx = static_cast<std::size_t>(m.nx), ny = static_cast<std::size_t>(m.ny);
  const double y0 = m.notch_y;
  auto row = [&](std::int64_t node) { return static_cast<std::size_t>(node) / nx; };

  std::vector<std::size_t> grip;
  for (std::size_t b = 0; b < m.bonds(); ++b) {
    const auto [i, j] = m.bond[b];
    const bool broken = f.intact[b] == 0;
    const double yi = m.position[static_cast<std::size_t>(i)].y(), yj = m.position[static_cast<std::size_t>(j)].y();
    if ((yi < y0) != (yj < y0)) {  // across the crack line
      if (!broken) continue;
      ++s.broken_crossing;
      const double x = m.position[static_cast<std::size_t>(i)].x() +
                       (m.position[static_cast<std::size_t>(j)].x() - m.position[static_cast<std::size_t>(i)].x()) *
                           (yi - y0) / (yi - yj);
      if (!s.tip_found || x > s.tip_reference_x) {
        s.tip_found = true;
        s.tip_reference_x = x;
        s.tip_x = 0.5 * (f.position[2 * static_cast<std::size_t>(i)] + f.position[2 * static_cast<std::size_t>(j)]);
      }
      continue;
    }
    if (broken) ++s.broken_bulk;
    const std::size_t ri = row(i), rj = row(j);  // i < j: rj = ri or ri + 1
    if (ri != rj && (ri + 1 == clamp_rows || rj + clamp_rows == ny)) grip.push_back(b);
  }
  for (std::size_t b : grip) {
    const auto [i, j] = m.bond[b];
    if (!s.tip_found || m.position[static_cast<std::size_t>(i)].x() + m.position[static_cast<std::size_t>(j)].x() >
                            2 * s.tip_reference_x)
      continue;
    ++s.grip_bonds;
    if (f.intact[b] == 0) ++s.grip_bonds_broken;
  }
}

// The opening front: in each row from the crack line halfway to the grips, the farthest node (with its two
// neighbours) that has let go; straight lines through the rows above, below and both.
void fit_front(const mesh::NodeMesh& m, const io::BodyFrame& f, double stretch_x, double stretch_y,
               std::size_t clamp_rows, CrackShape& s) {
  const std::size_t nx = static_cast<std::size_t>(m.nx), ny = static_cast<std::size_t>(m.ny);
  const double y0 = m.notch_y;
  // A node has let go when it has moved more than a spacing from its place in the pre-stretched sheet: ahead
  // of a supersonic tip nothing has moved but the small waves of the seed's opening.
  auto moved = [&](std::size_t node) {
    return std::hypot(f.position[2 * node] - stretch_x * m.position[node].x(),
                      f.position[2 * node + 1] - stretch_y * m.position[node].y()) > m.spacing;
  };
  // The rows from the crack line halfway to the grips: further out the grips reflect and tear.
  const std::size_t half = (ny - 2 * clamp_rows) / 2;
  const double row_step = m.position[nx].y() - m.position[0].y();
  std::vector<std::array<double, 2>> upper, lower;
  for (std::size_t r = clamp_rows; r + clamp_rows < ny; ++r) {
    const std::size_t first = r * nx;
    const double ry = m.position[first].y();
    const auto from_line =
        static_cast<std::size_t>(std::lround(std::abs(ry - y0) / row_step - 0.5));  // rows in between
    if (2 * from_line >= half) continue;
    const double h = stretch_y * std::abs(ry - y0);  // the row's far-field lab distance from the line
    for (std::size_t c = nx; c-- > 2;)
      if (moved(first + c) && moved(first + c - 1) && moved(first + c - 2)) {
        (ry > y0 ? upper : lower).push_back({h, f.position[2 * (first + c)]});
        break;
      }
  }
  s.front_rows = upper.size() + lower.size();
  const Line lu = fit(upper), ll = fit(lower);
  std::vector<std::array<double, 2>> both = upper;
  both.insert(both.end(), lower.begin(), lower.end());
  const Line lb = fit(both);
  s.front_angle_upper = angle_to_line(lu);
  s.front_angle_lower = angle_to_line(ll);
  s.front_angle = angle_to_line(lb);
  if (lb.n >= 3) {
    double sum = 0;
    for (const auto& p : both) sum += (p[1] - lb.a - lb.s * p[0]) * (p[1] - lb.a - lb.s * p[0]);
    s.front_rms = std::sqrt(sum / static_cast<double>(lb.n));
    s.front_lag = s.tip_found ? s.tip_x - lb.a : kNaN;
  } else {
    s.front_rms = s.front_lag = kNaN;
  }
}

}  // namespace

CrackShape measure_crack_shape(const mesh::NodeMesh& m, const io::BodyFrame& f, double stretch_x, double stretch_y,
                               std::size_t clamp_rows) {
  if (m.rows_along != "x" || m.nx < 3 || m.ny < 2 * static_cast<std::int64_t>(clamp_rows) + 2)
    throw InputError("crack shape: needs a triangular mesh with rows along x and free rows between the clamps (got " +
                     std::to_string(m.nx) + " x " + std::to_string(m.ny) + ", rows along " + m.rows_along + ")");
  const std::size_t n = m.nodes(), nx = static_cast<std::size_t>(m.nx), ny = static_cast<std::size_t>(m.ny);
  if (f.position.size() != 2 * n || f.intact.size() != m.bonds() || f.strain.size() != m.bonds())
    throw InputError("crack shape: the frame does not match the mesh (" + std::to_string(n) + " nodes, " +
                     std::to_string(m.bonds()) + " bonds)");
  CrackShape s;
  s.time = f.time;
  count_broken_bonds(m, f, clamp_rows, s);
  fit_front(m, f, stretch_x, stretch_y, clamp_rows, s);

  // Free nodes far beyond the outer rows, which the clamps hold at their pre-stretched height.
  const double row_step = m.position[nx].y() - m.position[0].y();
  const double reach = 0.5 * static_cast<double>(ny - 2 * clamp_rows) * row_step;
  const double y_bottom = stretch_y * m.position[0].y() - reach;
  const double y_top = stretch_y * m.position[(ny - 1) * nx].y() + reach;
  s.free_nodes = (ny - 2 * clamp_rows) * nx;
  for (std::size_t i = clamp_rows * nx; i < (ny - clamp_rows) * nx; ++i) {
    const double y = f.position[2 * i + 1];
    if (y > y_top || y < y_bottom) ++s.nodes_past_grips;
  }
  return s;
}

}  // namespace frac::analysis