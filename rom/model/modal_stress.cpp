// Modal stress data (see modal_stress.hpp).
#include "rom/model/modal_stress.hpp"

#include "common/error.hpp"

namespace mastrom::rom {

void ModalStress::validate(int modes, bool check_values) const {
  if (interface_offsets.size() == 0) {
    MASTROM_REQUIRE(this->modes.size() == 0 && loads.size() == 0 && preload.size() == 0 &&
                        points.size() == 0,
                    InputError, "modal stresses: stress data without interfaces");
    return;
  }
  const Eigen::Index p = points.cols(), rows = kStressRowsPerPoint * p;
  MASTROM_REQUIRE(interface_offsets.size() >= 2 && interface_offsets[0] == 0 &&
                      interface_offsets[interface_offsets.size() - 1] == p,
                  InputError, "modal stresses: interface offsets do not cover the ", p, " points");
  for (Eigen::Index i = 1; i < interface_offsets.size(); ++i)
    MASTROM_REQUIRE(interface_offsets[i] > interface_offsets[i - 1], InputError,
                    "modal stresses: interface ", i, " has no recovery points");
  MASTROM_REQUIRE(this->modes.rows() == rows && this->modes.cols() == modes &&
                      loads.rows() == rows && loads.cols() == kStressLoadCount &&
                      preload.size() == rows,
                  InputError, "modal stresses: sizes disagree (", p, " points, ", modes,
                  " modes: expected ", rows, " rows)");
  if (!check_values) return;
  MASTROM_REQUIRE(this->modes.allFinite() && loads.allFinite() && preload.allFinite() &&
                      points.allFinite() && std::isfinite(damping_s) && damping_s >= 0.0,
                  InputError, "modal stresses: non-finite stress data or negative damping");
}

}  // namespace mastrom::rom
