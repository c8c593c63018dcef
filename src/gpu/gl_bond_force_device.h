// The bond forces of one bond-based body on the GPU, through an OpenGL compute shader
// (shaders/pd_bond_forces.comp) in fp64. The bonds (row offsets, neighbours, length classes, the
// inverse reference lengths, stiffness, no-fail flags) are uploaded once and stay on the GPU; the
// shader zeroes a bond's stiffness there when it breaks it, and the host's changes made outside an
// evaluation are uploaded again before the next. Positions (and velocities when damped) go up and
// the row sums come back at every evaluation: the rest of the step is on the CPU for now.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpu/gl_compute_context.h"
#include "pd/bond_force_device.h"

namespace periflex {

class GlBondForceDevice : public BondForceDevice {
 public:
  // groups_across: the most groups of 64 rows a dispatch lays along its first axis before it
  // continues on the second (the spec's floor 65535, reached at 4.2M particles; smaller in tests,
  // so that a small body takes the path a large one takes).
  explicit GlBondForceDevice(std::shared_ptr<GlComputeContext> context, unsigned groups_across = 65535);
  ~GlBondForceDevice() override;

  const std::string& description() const override { return context_->description(); }
  void upload(const BondStore& bonds, const uint8_t* no_fail) override;
  void bonds_changed() override { stiffness_stale_ = true; }
  void add_forces(BondStore& bonds, const DeviceEvaluation& e) override;
  // For benchmarks: the last evaluation's pass again on the positions already on the GPU, nothing
  // uploaded or read back; returns when the GPU has finished. What the pass costs once the state
  // is resident.
  void repeat_last_pass();

 private:
  enum Buffer {
    kRowOffsets, kNeighbors, kLengthClasses, kStiffness, kInvLengths, kPositions, kVelocities, kForces,
    kRowBroke, kRowMax, kNoFail, kBufferCount
  };
  std::shared_ptr<GlComputeContext> context_;
  unsigned buffers_[kBufferCount] = {};
  unsigned groups_across_;
  int particles_ = 0;
  bool has_no_fail_ = false;
  bool stiffness_stale_ = false;
  // the uniforms of the last pass (repeat_last_pass)
  struct Pass {
    bool damped = false, breaking = false, track = false;
    double eta_over_e = 0.0, s0 = 0.0;
  } last_;
  void dispatch(const Pass& pass);
  std::vector<double> row_sums_;     // forces read back
  std::vector<uint32_t> row_flags_;  // rows that broke a bond, read back
  std::vector<float> row_stiffness_; // a flagged row's stiffness as the GPU left it
};

// The factory the program installs (install_bond_force_device): one compute context, made on the
// first call and shared by every body's device. Throws std::runtime_error saying what is missing.
BondForceDeviceFactory gl_bond_force_device_factory(const std::string& resource_root);

// Whether an OpenGL compute context with fp64 can be made here; empty when it can, else why not.
std::string gl_compute_unavailable_reason(const std::string& resource_root);

}  // namespace periflex
