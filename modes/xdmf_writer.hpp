// Mode shapes for ParaView: an XDMF (version 2, read by ParaView's "XDMF Reader" and its Xdmf3
// readers) file that describes heavy data stored in an HDF5 file — usually the modes file itself,
// under /visualization:
//
//   /visualization/shell/points [P,3]            m     node positions r at the linearisation point
//   /visualization/shell/connectivity [E,4]      1     bilinear quad per shell element (its 4
//   corner
//                                                      nodes; the cubic interior is not drawn)
//   /visualization/shell/mode_NNN [P,3]          m     scaled mode displacement of the nodes
//   /visualization/modules/points [8B,3]         m     corners of every rigid module (a cube of
//   side
//                                                      d around its centroid, from the NCF
//                                                      coordinates r = A(c) q)
//   /visualization/modules/connectivity [B,8]    1     one hexahedron per module (VTK corner order)
//   /visualization/modules/mode_NNN [8B,3]       m     the corners' displacement A(c) φ
//
// The XDMF holds a temporal collection with one step per mode (Time = mode number 1 … k); each step
// is a spatial collection of the grids "shell" and "modules" with the point vector attribute
// "mode_shape" and <Information> entries frequency_hz and label. Each mode is scaled so its largest
// displayed displacement is `relative_amplitude` × the diagonal of the model's bounding box (the
// factor is stored as the attribute `scale` of every mode dataset; the mass-normalised shapes are
// in /modes/shapes). In ParaView: open the .xdmf, apply "Warp By Vector" (mode_shape), step through
// the modes with the time controls, and animate one mode by giving the warp's Scale Factor a
// sinusoidal key frame in the Animation View.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/hdf5_file.hpp"
#include "fullorder/multibody_system.hpp"

namespace mastrom::modes {

/// What writeModeVisualization stored (for writeXdmf).
struct VisualizationLayout {
  int shell_points = 0;
  int shell_cells = 0;
  int module_points = 0;
  int module_cells = 0;
  int modes = 0;
  std::vector<double> scales;  ///< per mode: displayed = scale × mass-normalised shape
  std::string group = "/visualization";
};

/// Write the /visualization datasets of the header into an open HDF5 file. `q` is the linearisation
/// point, `shapes` the modes (n_dof × k). Throws InputError on a size mismatch.
VisualizationLayout writeModeVisualization(h5::File& file, const fullorder::MultibodySystem& system,
                                           const Eigen::Ref<const Eigen::VectorXd>& q,
                                           const Eigen::Ref<const Eigen::MatrixXd>& shapes,
                                           double relative_amplitude = 0.1);

/// Write the XDMF file at `xdmf_path` (atomically: temporary name, then rename) that references the
/// datasets of `layout` in the HDF5 file `h5_reference` (as written into the XML, normally the HDF5
/// file's name relative to the XDMF file's directory). IoError on failure.
void writeXdmf(const std::string& xdmf_path, const std::string& h5_reference,
               const VisualizationLayout& layout,
               const Eigen::Ref<const Eigen::VectorXd>& frequencies_hz,
               const std::vector<std::string>& labels);

/// "dir/name.h5" → "dir/name.xdmf" (the extension replaced, or appended when there is none).
std::string xdmfPathFor(const std::string& h5_path);

}  // namespace mastrom::modes
