// Flat serialisation of a solved sample (see sample_exchange.hpp).
#include "rom/offline/sample_exchange.hpp"

#include "common/error.hpp"
#include "rom/model/modal_fields.hpp"

namespace mastrom::rom {
namespace {

class Reader {
public:
  explicit Reader(const std::vector<double>& b) : b_(b) {}
  double next() { return *take(1); }
  /// The next `count` values, or a NumericalError when the buffer ends before them.
  const double* take(std::size_t count) {
    MASTROM_REQUIRE(pos_ + count <= b_.size(), NumericalError,
                    "rom build: gathered sample data truncated");
    const double* p = b_.data() + pos_;
    pos_ += count;
    return p;
  }
  bool done() const { return pos_ >= b_.size(); }

private:
  const std::vector<double>& b_;
  std::size_t pos_ = 0;
};

ExchangedSample unpackSample(Reader& r) {
  ExchangedSample x;
  RomSample& s = x.sample;
  x.index = static_cast<int>(r.next());
  const int k = static_cast<int>(r.next()), kt = static_cast<int>(r.next());
  forEachModalField(s.modal, [&](const ModalFieldInfo& info, auto& member) {
    readRowMajor(member, info.shape, k, r.take(modalFieldSize(info.shape, k)));
  });
  const double* a = r.take(static_cast<std::size_t>(k) * kt);
  s.alignment.resize(k, kt);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < kt; ++j) s.alignment(i, j) = a[i * kt + j];
  s.tracking.resize(kt);
  s.tracking_sign.resize(kt);
  for (int j = 0; j < kt; ++j) s.tracking[j] = static_cast<int>(r.next());
  for (int j = 0; j < kt; ++j) s.tracking_sign[j] = static_cast<int>(r.next());
  for (int i = 0; i < 2; ++i) {
    x.mac_min[i] = r.next();
    x.mac_min_mode[i] = static_cast<int>(r.next());
  }
  for (double& t : x.times) t = r.next();
  // The modal stresses (an offsets count of 0: none).
  ModalStress& st = s.modal.stress;
  const int offsets = static_cast<int>(r.next());
  if (offsets > 0) {
    st.interface_offsets.resize(offsets);
    for (int i = 0; i < offsets; ++i) st.interface_offsets[i] = static_cast<int>(r.next());
    const Eigen::Index p = st.interface_offsets[offsets - 1], rows = kStressRowsPerPoint * p;
    const auto fill = [&r](Eigen::MatrixXd& m, Eigen::Index rr, Eigen::Index cc) {
      m = Eigen::Map<const Eigen::MatrixXd>(r.take(static_cast<std::size_t>(rr * cc)), rr, cc);
    };
    fill(st.modes, rows, k);
    fill(st.loads, rows, kStressLoadCount);
    st.preload = Eigen::Map<const Eigen::VectorXd>(r.take(static_cast<std::size_t>(rows)), rows);
    Eigen::MatrixXd points;
    fill(points, 2, p);
    st.points = points;
    st.damping_s = r.next();
  }
  return x;
}

}  // namespace

void packSample(std::vector<double>& b, const ExchangedSample& x) {
  const RomSample& s = x.sample;
  const int kt = static_cast<int>(s.tracking.size());
  b.push_back(x.index);
  b.push_back(s.modal.modeCount());
  b.push_back(kt);
  forEachModalField(s.modal, [&b](const ModalFieldInfo&, const auto& member) {
    appendRowMajor(b, member);
  });
  appendRowMajor(b, s.alignment);
  for (int j = 0; j < kt; ++j) b.push_back(s.tracking[j]);
  for (int j = 0; j < kt; ++j) b.push_back(s.tracking_sign[j]);
  for (int i = 0; i < 2; ++i) {
    b.push_back(x.mac_min[i]);
    b.push_back(x.mac_min_mode[i]);
  }
  for (double t : x.times) b.push_back(t);
  const ModalStress& st = s.modal.stress;
  b.push_back(static_cast<double>(st.interface_offsets.size()));
  if (st.empty()) return;
  for (Eigen::Index i = 0; i < st.interface_offsets.size(); ++i) b.push_back(st.interface_offsets[i]);
  const auto append = [&b](const auto& m) { b.insert(b.end(), m.data(), m.data() + m.size()); };
  append(st.modes);  // column-major, as the unpacking maps it
  append(st.loads);
  append(st.preload);
  append(st.points);
  b.push_back(st.damping_s);
}

std::vector<ExchangedSample> unpackSamples(const std::vector<double>& buffer) {
  std::vector<ExchangedSample> out;
  Reader reader(buffer);
  while (!reader.done()) out.push_back(unpackSample(reader));
  return out;
}

}  // namespace mastrom::rom
