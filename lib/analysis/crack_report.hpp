#pragma once
// The crack of a rubber-run file measured in one frame (analysis/crack_shape), beside the tip's speed at that
// frame and the Mach angles of the Mooney-Rivlin sheet at that speed: what `observables --crack-shape`
// prints and the rubber-crack experiment tabulates.
#include <iosfwd>

#include "analysis/crack_shape.hpp"
#include "io/hdf5.hpp"

namespace frac::analysis {

struct CrackReport {
  CrackShape shape;
  double speed = 0;         // m/s, the run's own tip-speed fit nearest the frame's time
  double mach_angle_T = 0;  // degrees, transverse and longitudinal Mach angles at `speed`
  double mach_angle_L = 0;
};

// The frame nearest `time` (s; NaN: the final frame). UsageError for a run that is not rubber-run's.
CrackReport crack_report(const io::Group& run, double time);

// `key value` lines.
void write_key_values(const CrackReport& report, std::ostream& out);

}  // namespace frac::analysis
