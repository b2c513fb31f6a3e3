// Interface stress histories resampled onto the output instants while a run goes (docs/theory.md
// §6.3 "Histories on the output grid"), so that a streamed result (fullorder/result_stream.hpp)
// holds a few evaluated instants, not the whole history.
//
// The monitor (fullorder/interface_stress.hpp) evaluates at the first state on or after each
// output instant; the histories are interpolated onto the output instants by the piecewise cubic
// through the four nearest evaluated instants of the same smooth piece (cubicStencil of
// fullorder/continuous_response.hpp). Which four is known once the evaluations reach two past τ
// and three past the piece's start, or the piece has ended, or the run has: the value at τ is
// then final, the same bits as InterfaceStressMonitor::resample of the whole history gives, and
// the instants no later output instant can use are dropped.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <deque>
#include <functional>
#include <vector>

namespace mastrom::fullorder {

struct InterfaceStressHistory;

/// Every interface's histories at one instant.
struct InterfaceStressRow {
  double time_s = 0.0;
  std::vector<double> max_von_mises_pa;                       ///< per interface
  std::vector<Eigen::Vector3d> base_force_n, base_moment_nm;  ///< per interface
  std::vector<Eigen::Vector3d> tip_force_n, tip_moment_nm;    ///< per interface
  void resize(std::size_t interfaces);
};
/// Receives the resampled rows in time order.
using InterfaceStressRowSink = std::function<void(const InterfaceStressRow&)>;

/// Append `row` to the histories `h` (one per interface).
void appendStressRow(const InterfaceStressRow& row, std::vector<InterfaceStressHistory>& h);

/// The histories `h` (one per interface, on the instants `t`) at τ by the cubic through the four
/// nearest instants of the piece [begin, end); the von Mises clipped at 0 (a cubic may dip below).
void interpolateStressRow(const std::vector<double>& t,
                          const std::vector<InterfaceStressHistory>& h, long begin, long end,
                          double tau, InterfaceStressRow& row);

class InterfaceStressResampler {
public:
  InterfaceStressResampler(std::size_t interfaces, InterfaceStressRowSink sink);

  /// An evaluated instant (later than the one before); piece_start: it opens a smooth piece.
  void addEvaluation(const InterfaceStressRow& row, bool piece_start);
  /// The next output instant (ascending); its row goes to the sink once it is final.
  void addOutputInstant(double time_s);
  /// The evaluations are over: every pending output instant within their span goes to the sink
  /// (one past it is dropped, as resample() drops it).
  void finish();

  std::size_t rowsEmitted() const { return emitted_; }
  /// Evaluated instants held (bounded whatever the horizon: the four of a stencil and a slack).
  std::size_t heldEvaluations() const { return t_.size(); }

private:
  /// Emit τ when its stencil is final; false when it must wait for more evaluations.
  bool resolve(double tau);
  /// Drop the instants before `keep_from` (window index).
  void dropBefore(long keep_from);

  InterfaceStressRowSink sink_;
  std::vector<double> t_;                  ///< the evaluated instants held
  std::vector<InterfaceStressHistory> h_;  ///< their values, per interface
  std::vector<long> starts_;               ///< window index of each piece start (first is 0)
  std::deque<double> pending_;             ///< output instants not yet final
  InterfaceStressRow row_;
  double first_time_s_ = 0.0;  ///< of the first evaluation (instants before it are dropped)
  bool finished_ = false;
  std::size_t emitted_ = 0;
};

}  // namespace mastrom::fullorder
