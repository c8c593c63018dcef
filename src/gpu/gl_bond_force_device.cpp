#include "gpu/gl_bond_force_device.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "render/gl.h"

namespace periflex {

namespace {

constexpr int kGroupSize = 64;  // local_size_x of pd_bond_forces.comp
constexpr unsigned kMaxGroupsAcross = 65535;  // GL_MAX_COMPUTE_WORK_GROUP_COUNT's floor in the spec

// Bytes packed four to a 32-bit word, as the shader reads them (byte_at).
std::vector<uint32_t> pack_bytes(const uint8_t* bytes, size_t count) {
  std::vector<uint32_t> words((count + 3) / 4 + 1, 0u);
  for (size_t k = 0; k < count; ++k) words[k / 4] |= static_cast<uint32_t>(bytes[k]) << (8 * (k % 4));
  return words;
}

void store(GLuint buffer, size_t bytes, const void* data, GLenum usage) {
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  // a buffer is never empty: a body without bonds still binds something
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes > 0 ? bytes : 8), bytes > 0 ? data : nullptr,
               usage);
}

void replace(GLuint buffer, size_t bytes, const void* data) {
  if (bytes == 0) return;
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
}

void read_back(GLuint buffer, size_t bytes, void* out) {
  if (bytes == 0) return;
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), out);
}

// The bonds of each row laid slot-major: value of bond k of row i at k n + i, `fill` where a row is
// shorter than the longest.
template <typename T, typename F>
std::vector<T> slot_major(const BondStore& bonds, int slots, T fill, F value_of) {
  const int n = bonds.particle_count();
  std::vector<T> out(static_cast<size_t>(slots) * n, fill);
  for (int i = 0; i < n; ++i)
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b)
      out[static_cast<size_t>(b - bonds.row[i]) * n + i] = value_of(i, b);
  return out;
}

// An error of the driver after `what`, as a DeviceError naming it (a lost context in words).
void check_device(const char* what) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  if (error == GL_CONTEXT_LOST)
    throw DeviceError(std::string("the GPU's context was lost in ") + what +
                      " (the driver reset it, or the GPU stalled or went away); the run stops here");
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", error);
  throw DeviceError(std::string("OpenGL error ") + code + " in " + what + "; the run stops here");
}

}  // namespace

GlBondForceDevice::GlBondForceDevice(std::shared_ptr<GlComputeContext> context, DevicePrecision precision,
                                     unsigned groups_across)
    : context_(std::move(context)),
      precision_(precision),
      program_(context_->bond_force_program(precision)),
      groups_across_(std::clamp(groups_across, 1u, kMaxGroupsAcross)),
      description_(std::string("OpenGL compute ") + precision_name(precision) + "; " + context_->description()) {
  EglContext::Scope current(context_->egl());
  glGenBuffers(kBufferCount, buffers_);
}

GlBondForceDevice::~GlBondForceDevice() {
  // at the process's exit a driver may have torn its EGL down first: then there is nothing to free
  EglContext::Scope current(context_->egl(), std::nothrow);
  if (current.current()) glDeleteBuffers(kBufferCount, buffers_);
}

void GlBondForceDevice::upload(const BondStore& bonds, const BondState& live, const uint8_t* no_fail,
                               const double* reference) {
  EglContext::Scope current(context_->egl());
  if (bonds.own_lengths()) throw DeviceError("the GPU path reads bond lengths from the grid; this body's particles are off it");
  if (bonds.own_break_stretches())
    throw DeviceError("the GPU path breaks every bond at one critical stretch; this body has materials by block");
  const int n = bonds.particle_count();
  int slots = 0;
  for (int i = 0; i < n; ++i) slots = std::max<int>(slots, static_cast<int>(bonds.row[i + 1] - bonds.row[i]));
  // the shader indexes slots with 32-bit unsigned integers
  if (static_cast<int64_t>(slots) * n > static_cast<int64_t>(std::numeric_limits<uint32_t>::max()))
    throw std::runtime_error("a body with more than 4.29e9 bond slots does not fit the GPU path");
  particles_ = n;
  slots_per_row_ = slots;
  words_ = std::max(1, (slots + 31) / 32);
  const bool fp32 = precision_ == DevicePrecision::kFp32;
  const size_t real = fp32 ? sizeof(float) : sizeof(double);

  std::vector<uint32_t> lengths(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) lengths[i] = static_cast<uint32_t>(bonds.row[i + 1] - bonds.row[i]);
  store(buffers_[kRowLengths], lengths.size() * sizeof(uint32_t), lengths.data(), GL_STATIC_DRAW);
  const auto neighbors = slot_major<int32_t>(bonds, slots, 0, [&](int, int64_t b) { return bonds.neighbor[b]; });
  store(buffers_[kNeighbors], neighbors.size() * sizeof(int32_t), neighbors.data(), GL_STATIC_DRAW);
  const auto classes = slot_major<uint8_t>(bonds, slots, 0, [&](int, int64_t b) { return bonds.length_class[b]; });
  const std::vector<uint32_t> packed = pack_bytes(classes.data(), classes.size());
  store(buffers_[kLengthClasses], packed.size() * sizeof(uint32_t), packed.data(), GL_STATIC_DRAW);
  store(buffers_[kStiffness], static_cast<size_t>(slots) * n * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
  upload_stiffness(bonds, live);
  if (fp32) {
    const std::vector<float> table(bonds.inv_length_table.begin(), bonds.inv_length_table.end());
    store(buffers_[kInvLengths], table.size() * sizeof(float), table.data(), GL_STATIC_DRAW);
    // the reference bond vectors, formed in double precision and rounded once
    std::vector<float> xi(2 * static_cast<size_t>(slots) * n, 0.0f);
    for (int i = 0; i < n; ++i)
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const size_t slot = static_cast<size_t>(b - bonds.row[i]) * n + i;
        const int j = bonds.neighbor[b];
        xi[2 * slot] = static_cast<float>(reference[2 * j] - reference[2 * i]);
        xi[2 * slot + 1] = static_cast<float>(reference[2 * j + 1] - reference[2 * i + 1]);
      }
    store(buffers_[kReferenceBonds], xi.size() * sizeof(float), xi.data(), GL_STATIC_DRAW);
    reference_.assign(reference, reference + 2 * static_cast<size_t>(n));
  } else {
    store(buffers_[kInvLengths], bonds.inv_length_table.size() * sizeof(double), bonds.inv_length_table.data(),
          GL_STATIC_DRAW);
    store(buffers_[kReferenceBonds], 0, nullptr, GL_STATIC_DRAW);
  }
  const size_t coordinates = 2 * static_cast<size_t>(n) * real;
  store(buffers_[kPositions], coordinates, nullptr, GL_STREAM_DRAW);
  store(buffers_[kVelocities], coordinates, nullptr, GL_STREAM_DRAW);
  store(buffers_[kForces], coordinates, nullptr, GL_STREAM_READ);
  store(buffers_[kBrokeBits], static_cast<size_t>(words_) * n * sizeof(uint32_t), nullptr, GL_STREAM_READ);
  store(buffers_[kRowMax], static_cast<size_t>(n) * real, nullptr, GL_STREAM_READ);
  has_no_fail_ = no_fail != nullptr;
  const std::vector<uint32_t> fixed = no_fail ? pack_bytes(no_fail, n) : std::vector<uint32_t>(1, 0u);
  store(buffers_[kNoFail], fixed.size() * sizeof(uint32_t), fixed.data(), GL_STATIC_DRAW);
  check_gl("uploading the bonds to the GPU");
  stiffness_stale_ = false;
}

void GlBondForceDevice::upload_stiffness(const BondStore& bonds, const BondState& live) {
  slots_ = slot_major<float>(bonds, slots_per_row_, 0.0f, [&](int, int64_t b) { return live.stiffness[b]; });
  replace(buffers_[kStiffness], slots_.size() * sizeof(float), slots_.data());
}

void GlBondForceDevice::upload_state(const DeviceEvaluation& e, bool damped) {
  const size_t count = 2 * static_cast<size_t>(particles_);
  if (precision_ == DevicePrecision::kFp64) {
    replace(buffers_[kPositions], count * sizeof(double), e.pos);
    if (damped) replace(buffers_[kVelocities], count * sizeof(double), e.vel);
    return;
  }
  // fp32: displacements from the reference, small numbers that single precision holds to 6e-8
  slots_.resize(count);
  for (size_t c = 0; c < count; ++c) slots_[c] = static_cast<float>(e.pos[c] - reference_[c]);
  replace(buffers_[kPositions], count * sizeof(float), slots_.data());
  if (damped) {
    for (size_t c = 0; c < count; ++c) slots_[c] = static_cast<float>(e.vel[c]);
    replace(buffers_[kVelocities], count * sizeof(float), slots_.data());
  }
}

void GlBondForceDevice::read_forces(const DeviceEvaluation& e) {
  const size_t count = 2 * static_cast<size_t>(particles_);
  // the row sums, added as the CPU loop adds its own
  if (precision_ == DevicePrecision::kFp64) {
    row_sums_.resize(count);
    read_back(buffers_[kForces], count * sizeof(double), row_sums_.data());
    for (size_t c = 0; c < count; ++c) e.force[c] += row_sums_[c];
  } else {
    slots_.resize(count);
    read_back(buffers_[kForces], count * sizeof(float), slots_.data());
    for (size_t c = 0; c < count; ++c) e.force[c] += slots_[c];
  }
  if (!e.row_max) return;
  const size_t n = static_cast<size_t>(particles_);
  if (precision_ == DevicePrecision::kFp64) {
    read_back(buffers_[kRowMax], n * sizeof(double), e.row_max);
  } else {
    slots_.resize(n);
    read_back(buffers_[kRowMax], n * sizeof(float), slots_.data());
    for (size_t i = 0; i < n; ++i) e.row_max[i] = slots_[i];
  }
}

void GlBondForceDevice::mark_broken(const BondStore& bonds, BondState& live, const DeviceEvaluation& e) {
  // one bit per slot, word w of row i at w n + i: mark, as the CPU's cut_row_forces does, every
  // bond the GPU left out and the host still holds
  const size_t n = static_cast<size_t>(particles_);
  broke_bits_.resize(static_cast<size_t>(words_) * n);
  read_back(buffers_[kBrokeBits], broke_bits_.size() * sizeof(uint32_t), broke_bits_.data());
  for (int w = 0; w < words_; ++w)
    for (size_t i = 0; i < n; ++i) {
      uint32_t bits = broke_bits_[w * n + i];
      if (bits == 0u) continue;
      e.row_broke[i] = 1;
      for (; bits != 0u; bits &= bits - 1u) {
        const int64_t b = bonds.row[i] + 32 * w + __builtin_ctz(bits);
        if (live.stiffness[b] > 0.0f) live.broken[b] = 2;
      }
    }
}

void GlBondForceDevice::add_forces(const BondStore& bonds, BondState& live, const DeviceEvaluation& e) {
  if (bonds.particle_count() != particles_) throw std::logic_error("GPU bond forces: the bonds were not uploaded");
  if (particles_ == 0) return;
  EglContext::Scope current(context_->egl());
  if (stiffness_stale_) {
    upload_stiffness(bonds, live);
    stiffness_stale_ = false;
  }
  const bool damped = e.eta_over_e > 0.0 && e.vel;
  upload_state(e, damped);
  last_ = Pass{damped, e.breaking, e.row_max != nullptr, damped ? e.eta_over_e : 0.0, e.s0};
  dispatch(last_);
  read_forces(e);
  if (e.breaking) mark_broken(bonds, live, e);
  check_device("the GPU bond-force pass");
}

void GlBondForceDevice::dispatch(const Pass& pass) {
  glUseProgram(program_);
  for (int b = 0; b < kBufferCount; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers_[b]);
  glUniform1ui(glGetUniformLocation(program_, "u_count"), static_cast<GLuint>(particles_));
  glUniform1ui(glGetUniformLocation(program_, "u_words"), static_cast<GLuint>(words_));
  glUniform1i(glGetUniformLocation(program_, "u_damped"), pass.damped ? 1 : 0);
  glUniform1i(glGetUniformLocation(program_, "u_breaking"), pass.breaking ? 1 : 0);
  glUniform1i(glGetUniformLocation(program_, "u_track"), pass.track ? 1 : 0);
  glUniform1i(glGetUniformLocation(program_, "u_has_no_fail"), has_no_fail_ ? 1 : 0);
  if (precision_ == DevicePrecision::kFp64) {
    glUniform1d(glGetUniformLocation(program_, "u_eta_over_e"), pass.eta_over_e);
    glUniform1d(glGetUniformLocation(program_, "u_s0"), pass.s0);
  } else {
    glUniform1f(glGetUniformLocation(program_, "u_eta_over_e"), static_cast<float>(pass.eta_over_e));
    glUniform1f(glGetUniformLocation(program_, "u_s0"), static_cast<float>(pass.s0));
  }
  // a dispatch has at most 65535 groups along an axis (the least every driver gives): larger
  // bodies take rows of groups on the second axis, the shader's row index spanning both
  const GLuint groups = static_cast<GLuint>((particles_ + kGroupSize - 1) / kGroupSize);
  const GLuint across = std::min<GLuint>(groups, groups_across_);
  glDispatchCompute(across, (groups + across - 1) / across, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

double GlBondForceDevice::free_memory() {
  EglContext::Scope current(context_->egl());
  constexpr GLenum kNvidiaAvailable = 0x9049;  // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, kB
  constexpr GLenum kAmdFree = 0x87FC;          // GL_TEXTURE_FREE_MEMORY_ATI: free kB first of four
  while (glGetError() != GL_NO_ERROR) {
  }
  // a query the driver does not know raises GL_INVALID_ENUM and leaves the value alone
  for (GLenum query : {kNvidiaAvailable, kAmdFree}) {
    GLint values[4] = {-1, -1, -1, -1};
    glGetIntegerv(query, values);
    if (glGetError() == GL_NO_ERROR && values[0] >= 0) return static_cast<double>(values[0]) * 1024.0;
  }
  return -1.0;
}

void GlBondForceDevice::repeat_last_pass() {
  if (particles_ == 0) return;
  EglContext::Scope current(context_->egl());
  dispatch(last_);
  glFinish();
  check_device("the GPU bond-force pass");
}

BondForceDeviceFactory gl_bond_force_device_factory(const std::string& resource_root) {
  // the context is made by the first body that asks, on its thread, and shared by the others
  auto shared = std::make_shared<std::shared_ptr<GlComputeContext>>();
  auto once = std::make_shared<std::mutex>();
  return [resource_root, shared, once](DevicePrecision precision) -> std::unique_ptr<BondForceDevice> {
    std::lock_guard<std::mutex> lock(*once);
    if (!*shared) *shared = std::make_shared<GlComputeContext>(resource_root);
    return std::make_unique<GlBondForceDevice>(*shared, precision);
  };
}

std::string gl_compute_unavailable_reason(const std::string& resource_root, DevicePrecision precision) {
  try {
    GlComputeContext probe(resource_root);
    probe.bond_force_program(precision);
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace periflex
