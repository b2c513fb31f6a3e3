// A fixed modal model behind the interpolator interface: a direct solve's model as the reference
// of an evaluation (rom/studies/rom_evaluation.hpp) at any point.
#pragma once

#include <utility>
#include <vector>

#include "rom/interpolation/interpolator.hpp"

namespace mastrom::rom::testing {

class FixedModel final : public ModalInterpolator {
public:
  explicit FixedModel(ModalModel m) : m_(std::move(m)) {}
  ModalModel evaluate(const std::vector<double>&) const override { return m_; }
  ModalModel evaluateWithStresses(const std::vector<double>&) const override { return m_; }

private:
  ModalModel m_;
};

}  // namespace mastrom::rom::testing
