// The small mast the deployment tests run on: Scheme 1 (2 modules, 1 interface) on a 1 × 6 ring.
// Short horizons and this coarse ring keep each case to a fraction of a second; what the tests
// check (rigid-body mechanics, energy, solver paths) does not depend on the mesh.
#pragma once

#include "common/config.hpp"

namespace mastrom::fullorder::testing {

inline Config coarseScheme1() {
  Config c;
  c.mast.modules = 2;
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 6;
  return c;
}

}  // namespace mastrom::fullorder::testing
