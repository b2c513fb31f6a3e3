// Interface stress histories resampled while a run goes (see interface_stress_stream.hpp).
#include "fullorder/interface_stress_stream.hpp"

#include <algorithm>
#include <utility>

#include "fullorder/continuous_response.hpp"
#include "fullorder/interface_stress.hpp"

namespace mastrom::fullorder {
namespace {

/// Σ_a w_a · column[first + a] (the cubic of continuous_response.hpp).
template <class T>
T mixColumn(const CubicStencil& st, const std::vector<T>& column) {
  T v = st.weight[0] * column[static_cast<size_t>(st.first)];
  for (int a = 1; a < st.count; ++a) v += st.weight[a] * column[static_cast<size_t>(st.first + a)];
  return v;
}

/// Evaluated instants kept in front of a stencil before the window is compacted: erasing the
/// front every few hundred rows keeps the cost per instant constant.
constexpr long kCompactRows = 64;

}  // namespace

void InterfaceStressRow::resize(std::size_t interfaces) {
  max_von_mises_pa.resize(interfaces);
  base_force_n.resize(interfaces);
  base_moment_nm.resize(interfaces);
  tip_force_n.resize(interfaces);
  tip_moment_nm.resize(interfaces);
}

void appendStressRow(const InterfaceStressRow& row, std::vector<InterfaceStressHistory>& h) {
  for (std::size_t k = 0; k < h.size(); ++k) {
    h[k].max_von_mises_pa.push_back(row.max_von_mises_pa[k]);
    h[k].base_force_n.push_back(row.base_force_n[k]);
    h[k].base_moment_nm.push_back(row.base_moment_nm[k]);
    h[k].tip_force_n.push_back(row.tip_force_n[k]);
    h[k].tip_moment_nm.push_back(row.tip_moment_nm[k]);
  }
}

void interpolateStressRow(const std::vector<double>& t,
                          const std::vector<InterfaceStressHistory>& h, long begin, long end,
                          double tau, InterfaceStressRow& row) {
  const CubicStencil st = cubicStencil(t, begin, end, tau);
  row.resize(h.size());
  row.time_s = tau;
  for (std::size_t k = 0; k < h.size(); ++k) {
    row.max_von_mises_pa[k] = std::max(0.0, mixColumn(st, h[k].max_von_mises_pa));
    row.base_force_n[k] = mixColumn(st, h[k].base_force_n);
    row.base_moment_nm[k] = mixColumn(st, h[k].base_moment_nm);
    row.tip_force_n[k] = mixColumn(st, h[k].tip_force_n);
    row.tip_moment_nm[k] = mixColumn(st, h[k].tip_moment_nm);
  }
}

InterfaceStressResampler::InterfaceStressResampler(std::size_t interfaces,
                                                   InterfaceStressRowSink sink)
    : sink_(std::move(sink)), h_(interfaces) {
  row_.resize(interfaces);
}

void InterfaceStressResampler::addEvaluation(const InterfaceStressRow& row, bool piece_start) {
  if (t_.empty() && starts_.empty()) first_time_s_ = row.time_s;
  if (piece_start || starts_.empty()) starts_.push_back(static_cast<long>(t_.size()));
  t_.push_back(row.time_s);
  appendStressRow(row, h_);
  while (!pending_.empty() && resolve(pending_.front())) pending_.pop_front();
}

void InterfaceStressResampler::addOutputInstant(double time_s) {
  pending_.push_back(time_s);
  while (!pending_.empty() && resolve(pending_.front())) pending_.pop_front();
}

void InterfaceStressResampler::finish() {
  finished_ = true;
  while (!pending_.empty()) {
    if (!resolve(pending_.front())) break;
    pending_.pop_front();
  }
  pending_.clear();  // past the last evaluation: dropped, as resample() drops them
}

bool InterfaceStressResampler::resolve(double tau) {
  if (t_.empty()) return finished_;  // nothing evaluated: wait, or drop at the end
  // resample()'s span: instants outside the evaluated one (by more than round-off) are dropped.
  if (tau < first_time_s_ - 1e-12) return true;
  const long n = static_cast<long>(t_.size());
  if (!finished_ && !(t_.back() > tau)) return false;  // a later piece start may still come
  if (finished_ && tau > t_.back() + 1e-12) return true;
  // The piece holding τ by its start time (the first piece for an instant before every start).
  std::size_t piece = 0;
  while (piece + 1 < starts_.size() && t_[static_cast<size_t>(starts_[piece + 1])] <= tau) ++piece;
  const long begin = starts_[piece];
  const bool closed = finished_ || piece + 1 < starts_.size();
  const long end = piece + 1 < starts_.size() ? starts_[piece + 1] : n;
  const long i = std::max(
      begin,
      static_cast<long>(std::upper_bound(t_.begin() + begin, t_.begin() + end, tau) - t_.begin()) -
          1);
  // An open piece: its stencil at τ is final once the piece holds two instants past τ's interval
  // and four in all (then cubicStencil's count is 4 and its first max(i − 1, begin), whatever
  // follows).
  if (!closed && n - 1 < std::max(i + 2, begin + 3)) return false;
  interpolateStressRow(t_, h_, begin, end, tau, row_);
  sink_(row_);
  ++emitted_;
  // Later instants lie at or after τ: their stencils start at i − 3 or later (the clamp to the
  // piece's end moves a stencil back by at most two), or in a later piece.
  dropBefore(i - 3);
  return true;
}

void InterfaceStressResampler::dropBefore(long keep_from) {
  if (keep_from < kCompactRows) return;
  const auto cut = [keep_from](auto& column) {
    column.erase(column.begin(), column.begin() + keep_from);
  };
  cut(t_);
  for (InterfaceStressHistory& h : h_) {
    cut(h.max_von_mises_pa);
    cut(h.base_force_n);
    cut(h.base_moment_nm);
    cut(h.tip_force_n);
    cut(h.tip_moment_nm);
  }
  // The piece the window now starts in begins at 0; the pieces wholly before it are gone.
  std::vector<long> starts{0};
  for (long s : starts_)
    if (s - keep_from > 0) starts.push_back(s - keep_from);
  starts_ = std::move(starts);
}

}  // namespace mastrom::fullorder
