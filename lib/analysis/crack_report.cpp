#include "analysis/crack_report.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <ostream>
#include <string>

#include "analysis/mooney_rivlin_waves.hpp"
#include "analysis/observable_table.hpp"
#include "core/error.hpp"
#include "io/mesh_io.hpp"
#include "io/run_io.hpp"

namespace frac::analysis {

CrackReport crack_report(const io::Group& root, double time) {
  const io::RunInfo info = io::read_run_info(root);
  if (info.model != "rubber") throw UsageError("--crack-shape: needs a rubber-run file");
  const auto number = [&](const std::string& key) { return std::stod(run_parameter(root, key)); };
  const io::BodyFrame frame = io::read_frame(root, std::isnan(time) ? -1 : io::frame_at_time(info, time));
  const Stretch stretch{number("loading.stretch_x"), number("loading.stretch_y")};
  CrackReport r;
  r.shape = measure_crack_shape(io::read_node_mesh(root), frame, stretch.x, stretch.y,
                                static_cast<std::size_t>(number("boundary.clamp_rows")));
  const ObservableTable speeds = read_observables(root, {"crack_tip_speed"});
  r.speed = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < speeds.time.size(); ++k)
    if (k == 0 || std::abs(speeds.time[k] - r.shape.time) <= std::abs(speeds.time[k - 1] - r.shape.time))
      r.speed = speeds.columns[0][k];
  const MooneyRivlin material{number("material.a"), number("material.b"), 1.0};
  const double degrees = 180.0 / std::numbers::pi;
  r.mach_angle_T = degrees * mach_angle(material, stretch, r.speed, false);
  r.mach_angle_L = degrees * mach_angle(material, stretch, r.speed, true);
  return r;
}

void write_key_values(const CrackReport& r, std::ostream& out) {
  const CrackShape& s = r.shape;
  out << std::setprecision(6) << "time " << s.time << "\ntip_found " << s.tip_found << "\ntip_reference_x "
      << s.tip_reference_x << "\ntip_x " << s.tip_x << "\nspeed " << r.speed << "\nbroken_crossing "
      << s.broken_crossing << "\nbroken_bulk " << s.broken_bulk << "\nfront_angle " << s.front_angle
      << "\nfront_angle_upper " << s.front_angle_upper << "\nfront_angle_lower " << s.front_angle_lower
      << "\nfront_rows " << s.front_rows << "\nfront_rms " << s.front_rms << "\nfront_lag " << s.front_lag
      << "\nmach_angle_T " << r.mach_angle_T << "\nmach_angle_L " << r.mach_angle_L << "\ngrip_bonds " << s.grip_bonds
      << "\ngrip_bonds_broken " << s.grip_bonds_broken << "\nfree_nodes " << s.free_nodes << "\nnodes_past_grips "
      << s.nodes_past_grips << "\n";
}

}  // namespace frac::analysis
