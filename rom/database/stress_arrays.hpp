// The modal stresses of a database's samples (rom/model/modal_stress.hpp) as the named arrays of
// its /stress group (docs/user_guide.md "Files"):
//   /stress/interface_offsets [I+1]  1      point offsets of the interfaces (all samples alike)
//   /stress/modes [S, R, k]          Pa     S per unit η (R = 6 rows per recovery point)
//   /stress/loads [S, R, 4]          Pa     the static correction per unit θ̈, θ̇², g_x, g_y
//   /stress/preload [S, R]           Pa     σ̄
//   /stress/points [S, 2, P]         m, rad axial position and angle of every point
//   /stress/damping [S]              s      Kelvin–Voigt μ
// A database carries them for every sample or for none (an affine database, or one built by a
// mastrom without stress recovery).
#pragma once

#include <vector>

#include "rom/database/affine_reduced.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// True when every sample carries stresses on the same mesh (the first sample's offsets and point
/// count). False when none does; InputError when only some do or their meshes differ.
bool databaseHasStresses(const RomDatabase& db);

/// The arrays above, in file order (empty without stresses).
std::vector<NamedArray> stressArrays(const RomDatabase& db);

/// Fill every sample's ModalModel::stress from the arrays (names as above, shapes checked against
/// the database's sample and mode counts). InputError naming the array on a missing one or a
/// wrong shape.
void assignStressArrays(const std::vector<NamedArray>& arrays, RomDatabase& db);

/// The array names, in file order.
const std::vector<const char*>& stressArrayNames();

}  // namespace mastrom::rom
