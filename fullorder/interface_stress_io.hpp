// The interface stresses of a deployment in its result file (docs/user_guide.md "Files"):
//
//   /interfaces/K/max_von_mises [N]                 Pa    largest von Mises of interface K over
//                                                         its points and ζ stations, per instant
//   /interfaces/K/{base,tip}/force [N,3]            N     [axial, shear u, shear v] at the edge
//   /interfaces/K/{base,tip}/moment [N,3]           N*m   [torsion, bending u, bending v]
//   /interfaces/K/{base,tip}/axial_force [N]        N     (force[:,0]; > 0 tension)
//   /interfaces/K/{base,tip}/shear_force [N]        N     |(force[:,1], force[:,2])|
//   /interfaces/K/{base,tip}/torsional_moment [N]   N*m   moment[:,0]
//   /interfaces/K/{base,tip}/bending_moment [N]     N*m   |(moment[:,1], moment[:,2])|
//   /interfaces/K/points [P,2]                      m, rad  axial position, angle of every
//                                                         element × recovery point (unrolled)
//   /interfaces/K/peak/von_mises_field [P,3]        Pa    von Mises at the peak instant, per point
//                                                         and ζ = −h/2, 0, +h/2 (along n, inward)
//   /interfaces/K/peak/points [P,3]                 m     the recovery points in the stowed mast
//   /interfaces/K/peak/cells [4E,4]                 1     quads between them (2 × 2 per element)
//   /interfaces/K/peak/von_mises_walls [P]          Pa    the larger of the two walls' von Mises
//   /interfaces/K/peak  attributes von_mises_pa, time_s, element, point, surface, axial_position_m,
//                       angle_rad
//   /interfaces/K/fields/N/von_mises_field [P,3]    Pa    the field at the N-th requested instant
//   /interfaces/K/fields/N/von_mises_walls [P]      Pa    (attributes requested_time_s, time_s)
//   /metrics attributes peak_von_mises_interface_K [Pa], and with a yield strength
//                       yield_strength [Pa], margin_of_safety_interface_K, min_margin_of_safety
//
// K = 1 … n − 1 (interface K joins modules K and K + 1, the paper's numbering). The histories share
// /time. With an XDMF companion (writeInterfaceStressXdmf) ParaView shows each peak field on the
// reference surface.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/hdf5_append.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/interface_stress.hpp"
#include "fullorder/results_io.hpp"

namespace mastrom::fullorder {

/// Scalar strength metrics of a deployment.
struct InterfaceStressMetrics {
  std::vector<double> peak_von_mises_pa;  ///< per interface
  std::vector<double> margin_of_safety;   ///< per interface (empty without a yield strength)
  std::optional<double> min_margin_of_safety;
};
InterfaceStressMetrics interfaceStressMetrics(const InterfaceStressResult& result,
                                              std::optional<double> yield_strength_pa);

/// The /metrics attributes of the layout above, in file order (name, SI value): what the file and
/// the Python module's metrics dict hold.
std::vector<std::pair<std::string, double>> interfaceStressMetricAttributes(
    const InterfaceStressResult& result, std::optional<double> yield_strength_pa);

/// Write the layout above into an open file. `time_count` = length of /time: the histories must
/// match it (UsageError otherwise); NumericalError on a non-finite value, before writing.
void writeInterfaceStresses(h5::File& file, const InterfaceStressResult& result,
                            std::size_t time_count, std::optional<double> yield_strength_pa);

/// writeInterfaceStresses without the histories: what a streamed run writes at its end, after
/// InterfaceStressAppender wrote the histories while it went.
void writeInterfaceStressResults(h5::File& file, const InterfaceStressResult& result,
                                 std::optional<double> yield_strength_pa);

/// The histories of the layout above as datasets that grow by rows (common/hdf5_append.hpp), fed
/// the rows a streamed run resamples (InterfaceStressMonitor::streamHistories): the same values,
/// units and attributes as writeInterfaceStresses writes from a whole history.
class InterfaceStressAppender {
public:
  /// Create the empty datasets of `interfaces` interfaces in `file` (which must outlive this);
  /// rows are buffered `block_rows` at a time. Without edge_resultants only max_von_mises (a ROM
  /// result's history: the rows' edge vectors are then not read).
  InterfaceStressAppender(h5::File& file, std::size_t interfaces, std::size_t block_rows,
                          bool edge_resultants = true);
  /// The next row; NumericalError naming the interface, the quantity and the time of a
  /// non-finite value (nothing of its block is written).
  void append(const InterfaceStressRow& row);
  std::size_t rows() const { return written_ + block_.size(); }
  /// Write the buffered rows and close the datasets; IoError on failure.
  void close();

private:
  struct Edge {
    h5::AppendableDataset force, moment, axial, shear, torsion, bending;
  };
  struct Interface {
    h5::AppendableDataset max_von_mises;
    Edge base, tip;
  };
  void writeBlock();

  std::vector<Interface> datasets_;
  std::vector<InterfaceStressRow> block_;
  std::size_t block_rows_;
  bool edges_;
  std::size_t written_ = 0;
};

/// What a comparison reads back of a file's interface stresses: per interface the history of the
/// largest von Mises stress and its peak [Pa].
struct InterfaceStressSummary {
  /// Per interface; empty where the file has no history (a ROM result without --stress-history).
  std::vector<std::vector<double>> max_von_mises_pa;
  std::vector<double> peak_von_mises_pa;
};
/// The summary of a deployment file's /interfaces, or nothing when it has none. IoError on a
/// malformed group.
std::optional<InterfaceStressSummary> readInterfaceStressSummary(const std::string& path);

/// writeDeploymentFile (fullorder/results_io.hpp) plus the interface stresses when given, in one
/// atomic write: every check runs before the file appears under its final name. `stopped_at_s`
/// set: the run stopped there before its end, and the file is marked incomplete (markIncomplete).
/// `extra` may add attributes or groups before the commit.
void writeDeploymentFileWithStresses(const std::string& path, const DeploymentSeries& series,
                                     const DeploymentMetrics& metrics,
                                     const std::string& resolved_config_toml, double wall_time_s,
                                     const std::optional<InterfaceStressResult>& stresses,
                                     std::optional<double> yield_strength_pa,
                                     ResultSource source = ResultSource::FullOrder,
                                     std::optional<double> stopped_at_s = std::nullopt,
                                     const std::function<void(h5::File&)>& extra = {});

/// The XDMF (version 2) file for ParaView that shows the stress fields from the HDF5 file
/// `h5_reference` (its name relative to the XDMF file): a temporal collection whose step 0 holds
/// every interface at its own peak and whose steps 1 … N the requested instants (von Mises of the
/// more stressed wall on /interfaces/K/peak/points and cells). Atomic; IoError on failure.
void writeInterfaceStressXdmf(const std::string& xdmf_path, const std::string& h5_reference,
                              const InterfaceStressResult& result);

/// Print one line per interface (peak, where, when, margin) to stdout.
void printInterfaceStressSummary(const InterfaceStressResult& result,
                                 std::optional<double> yield_strength_pa);

}  // namespace mastrom::fullorder
