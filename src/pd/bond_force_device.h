// The kernel seam of a flexible body: another processor (a GPU) evaluating a bond-based body's
// bond forces in place of the CPU loops of bond_kernel.h. Chosen at set-up: a body runs on the CPU
// unless the model hands it a device (PdBody::use_bond_force_device). The solver library holds
// only this interface and a registry; a device implementation (src/gpu/) lives above the solver
// and installs its factory at the program's start (install_bond_force_device), so the solver links
// no GL.
//
// What a device evaluates is exactly the CPU's force pass of the bond-based law: elastic forces,
// viscous bond damping, and, when asked, the in-evaluation break test (a breakable intact bond whose
// exact stretch exceeds s0 takes no part in the forces and is reported broken). The body settles
// the breaks on the host as the CPU path does (settle_broken_bonds), so energies, counts and the
// saved state do not depend on where the forces were computed.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "pd/bond_state.h"
#include "pd/bond_store.h"

namespace periflex {

// The arithmetic a device evaluates in. fp64: the CPU's formulas, the same breaks to the bit where
// the device's square root and division are correctly rounded. fp32: the displacement form
// (single-precision displacements from the reference and reference bond vectors, the stretch
// from their difference, so that no large coordinate cancels), half the memory traffic and a
// stretch within about 1e-7 of fp64's, so bonds at the edge of s0 may break a step apart.
enum class DevicePrecision { kFp64, kFp32 };
// "fp64" / "fp32", as solver.precision spells them, and back (anything else: fp64).
const char* precision_name(DevicePrecision precision);
DevicePrecision device_precision(const std::string& name);

// A device that failed mid-run: a lost context (a driver reset, a GPU removed or stalled past the
// watchdog), an error of the driver in a pass. The run stops as for a numerical failure (exit 3),
// the rows and frames written so far kept.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One evaluation on a device. Positions and velocities are interleaved [x0 y0 x1 y1 ...].
struct DeviceEvaluation {
  const double* pos = nullptr;
  const double* vel = nullptr;   // read only when eta_over_e > 0
  double eta_over_e = 0.0;       // bond damping eta / E; 0: elastic only
  double* force = nullptr;       // the row sums are added to it
  double* row_max = nullptr;     // when not null: each row's largest stretch over its intact bonds (-1: none)
  // the in-evaluation break test (add_bond_forces_breaking): when breaking, every breakable intact
  // bond past s0 is left out, marked broken = 2 in the body's BondState, and its row flagged in row_broke (n bytes,
  // all 0 on entry)
  bool breaking = false;
  double s0 = 0.0;
  uint8_t* row_broke = nullptr;
};

class BondForceDevice {
 public:
  virtual ~BondForceDevice() = default;
  // What runs the evaluations, e.g. "OpenGL 4.5 compute fp64; renderer: llvmpipe (LLVM 15.0.7, 256 bits)".
  virtual const std::string& description() const = 0;
  // Bytes of memory the device has free now; negative when its driver does not say.
  virtual double free_memory() { return -1.0; }
  // Takes the body's bonds (topology; stiffness from `live`), no-fail flags (null: none) and
  // reference positions (interleaved, 2 n), once; the device keeps them for every later evaluation.
  virtual void upload(const BondStore& bonds, const BondState& live, const uint8_t* no_fail,
                      const double* reference) = 0;
  // The host changed stiffness or broken flags outside an evaluation (a break pass after the step,
  // the knife, a restored state): the device takes them again before its next evaluation.
  virtual void bonds_changed() = 0;
  // One evaluation of the bonds last uploaded (see DeviceEvaluation); with e.breaking, also marks
  // the bonds it left out in live.broken.
  virtual void add_forces(const BondStore& bonds, BondState& live, const DeviceEvaluation& e) = 0;
};

// Bytes a device holds for bodies of `particles` particles and `directed_bonds` stored bond
// directions (each bond counted from both ends) in that precision: per stored direction its slot
// (neighbour 4, length class 1, stiffness 4; fp32 also the reference bond vector, 8), per particle
// its row length, break bits, no-fail flag and state (positions, velocities, forces, row maximum).
double device_bytes_needed(double particles, double directed_bonds, DevicePrecision precision);

// Makes a device for one body; throws std::runtime_error saying what is missing when it cannot.
using BondForceDeviceFactory = std::function<std::unique_ptr<BondForceDevice>(DevicePrecision)>;

// Installs the factory make_bond_force_device calls (the program does at its start; empty: none).
void install_bond_force_device(BondForceDeviceFactory factory);
// True when a factory is installed.
bool bond_force_device_installed();
// A new device of the given precision from the installed factory; throws std::runtime_error when none is installed or
// the factory cannot make one.
std::unique_ptr<BondForceDevice> make_bond_force_device(DevicePrecision precision = DevicePrecision::kFp64);

}  // namespace periflex
