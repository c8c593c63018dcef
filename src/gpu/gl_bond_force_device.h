// The bond forces of one bond-based body on the GPU, through an OpenGL compute shader
// (shaders/pd_bond_forces.comp) in fp64 or fp32. The bonds (row lengths, neighbours, length
// classes, the inverse reference lengths, stiffness, no-fail flags; in fp32 also the reference
// bond vectors) are uploaded once, slot-major, and stay on the GPU; the shader zeroes a bond's
// stiffness there when it breaks it, and the host's changes made outside an evaluation are uploaded
// again before the next. Positions (and velocities when damped) go up and the row sums come back
// at every evaluation: the rest of the step is on the CPU for now.
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
  // so that a small body takes the path a large one takes). Compiles the program of the precision
  // (throws std::runtime_error when the driver cannot).
  explicit GlBondForceDevice(std::shared_ptr<GlComputeContext> context,
                             DevicePrecision precision = DevicePrecision::kFp64, unsigned groups_across = 65535);
  ~GlBondForceDevice() override;

  const std::string& description() const override { return description_; }
  DevicePrecision precision() const { return precision_; }
  // From NVIDIA's GL_NVX_gpu_memory_info or AMD's GL_ATI_meminfo; negative where neither answers
  // (Mesa's llvmpipe, Intel).
  double free_memory() override;
  void upload(const BondStore& bonds, const BondState& live, const uint8_t* no_fail,
              const double* reference) override;
  void bonds_changed() override { stiffness_stale_ = true; }
  void add_forces(const BondStore& bonds, BondState& live, const DeviceEvaluation& e) override;
  // For benchmarks: the last evaluation's pass again on the positions already on the GPU, nothing
  // uploaded or read back; returns when the GPU has finished. What the pass costs once the state
  // is resident.
  void repeat_last_pass();

 private:
  enum Buffer {
    kRowLengths, kNeighbors, kLengthClasses, kStiffness, kInvLengths, kPositions, kVelocities, kForces,
    kBrokeBits, kRowMax, kNoFail, kReferenceBonds, kBufferCount
  };
  // the uniforms of one pass
  struct Pass {
    bool damped = false, breaking = false, track = false;
    double eta_over_e = 0.0, s0 = 0.0;
  };
  void dispatch(const Pass& pass);
  // the host's stiffness, slot-major, to the GPU
  void upload_stiffness(const BondStore& bonds, const BondState& live);
  // what an evaluation reads, in the device's precision: positions (fp32: displacements from the
  // reference) and velocities
  void upload_state(const DeviceEvaluation& e, bool damped);
  void read_forces(const DeviceEvaluation& e);
  void mark_broken(const BondStore& bonds, BondState& live, const DeviceEvaluation& e);

  std::shared_ptr<GlComputeContext> context_;
  DevicePrecision precision_;
  unsigned program_ = 0;
  unsigned groups_across_;
  std::string description_;
  unsigned buffers_[kBufferCount] = {};
  int particles_ = 0;
  int slots_per_row_ = 0;  // the longest row's bonds
  int words_ = 1;          // words of break bits per row: one bit per slot
  bool has_no_fail_ = false;
  bool stiffness_stale_ = false;
  Pass last_;
  std::vector<double> reference_;         // fp32: the reference positions, to form displacements
  std::vector<float> slots_;              // scratch: stiffness slot-major, fp32 state and forces
  std::vector<double> row_sums_;          // fp64 forces read back
  std::vector<uint32_t> broke_bits_;      // read back
};

// The factory the program installs (install_bond_force_device): one compute context, made on the
// first call and shared by every body's device. Throws std::runtime_error saying what is missing.
BondForceDeviceFactory gl_bond_force_device_factory(const std::string& resource_root);

// Whether an OpenGL compute context of that precision can be made here; empty when it can, else
// why not.
std::string gl_compute_unavailable_reason(const std::string& resource_root,
                                          DevicePrecision precision = DevicePrecision::kFp64);

}  // namespace periflex
