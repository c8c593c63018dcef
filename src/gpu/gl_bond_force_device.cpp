#include "gpu/gl_bond_force_device.h"

#include <algorithm>
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

void read_back(GLuint buffer, size_t offset, size_t bytes, void* out) {
  if (bytes == 0) return;
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
}

}  // namespace

GlBondForceDevice::GlBondForceDevice(std::shared_ptr<GlComputeContext> context, unsigned groups_across)
    : context_(std::move(context)), groups_across_(std::clamp(groups_across, 1u, kMaxGroupsAcross)) {
  EglContext::Scope current(context_->egl());
  glGenBuffers(kBufferCount, buffers_);
}

GlBondForceDevice::~GlBondForceDevice() {
  // at the process's exit a driver may have torn its EGL down first: then there is nothing to free
  EglContext::Scope current(context_->egl(), std::nothrow);
  if (current.current()) glDeleteBuffers(kBufferCount, buffers_);
}

void GlBondForceDevice::upload(const BondStore& bonds, const uint8_t* no_fail) {
  EglContext::Scope current(context_->egl());
  const int n = bonds.particle_count();
  const int64_t directed = bonds.directed_count();
  // the shader indexes bonds with 32-bit unsigned offsets
  if (directed > static_cast<int64_t>(std::numeric_limits<uint32_t>::max()))
    throw std::runtime_error("a body with more than 4.29e9 stored bond directions does not fit the GPU path");
  particles_ = n;
  std::vector<uint32_t> offsets(bonds.row.begin(), bonds.row.end());
  if (offsets.empty()) offsets.push_back(0u);
  store(buffers_[kRowOffsets], offsets.size() * sizeof(uint32_t), offsets.data(), GL_STATIC_DRAW);
  store(buffers_[kNeighbors], bonds.neighbor.size() * sizeof(int32_t), bonds.neighbor.data(), GL_STATIC_DRAW);
  const std::vector<uint32_t> classes = pack_bytes(bonds.length_class.data(), bonds.length_class.size());
  store(buffers_[kLengthClasses], classes.size() * sizeof(uint32_t), classes.data(), GL_STATIC_DRAW);
  store(buffers_[kStiffness], bonds.stiffness.size() * sizeof(float), bonds.stiffness.data(), GL_DYNAMIC_DRAW);
  store(buffers_[kInvLengths], bonds.inv_length_table.size() * sizeof(double), bonds.inv_length_table.data(),
        GL_STATIC_DRAW);
  const size_t coordinates = 2 * static_cast<size_t>(n) * sizeof(double);
  store(buffers_[kPositions], coordinates, nullptr, GL_STREAM_DRAW);
  store(buffers_[kVelocities], coordinates, nullptr, GL_STREAM_DRAW);
  store(buffers_[kForces], coordinates, nullptr, GL_STREAM_READ);
  store(buffers_[kRowBroke], static_cast<size_t>(n) * sizeof(uint32_t), nullptr, GL_STREAM_READ);
  store(buffers_[kRowMax], static_cast<size_t>(n) * sizeof(double), nullptr, GL_STREAM_READ);
  has_no_fail_ = no_fail != nullptr;
  const std::vector<uint32_t> fixed = no_fail ? pack_bytes(no_fail, n) : std::vector<uint32_t>(1, 0u);
  store(buffers_[kNoFail], fixed.size() * sizeof(uint32_t), fixed.data(), GL_STATIC_DRAW);
  check_gl("uploading the bonds to the GPU");
  stiffness_stale_ = false;
}

void GlBondForceDevice::add_forces(BondStore& bonds, const DeviceEvaluation& e) {
  if (bonds.particle_count() != particles_) throw std::logic_error("GPU bond forces: the bonds were not uploaded");
  const int n = particles_;
  if (n == 0) return;
  EglContext::Scope current(context_->egl());
  if (stiffness_stale_) {
    replace(buffers_[kStiffness], bonds.stiffness.size() * sizeof(float), bonds.stiffness.data());
    stiffness_stale_ = false;
  }
  const size_t coordinates = 2 * static_cast<size_t>(n) * sizeof(double);
  const bool damped = e.eta_over_e > 0.0 && e.vel;
  replace(buffers_[kPositions], coordinates, e.pos);
  if (damped) replace(buffers_[kVelocities], coordinates, e.vel);
  if (e.breaking) {
    const uint32_t zero = 0u;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[kRowBroke]);
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  }

  last_ = Pass{damped, e.breaking, e.row_max != nullptr, damped ? e.eta_over_e : 0.0, e.s0};
  dispatch(last_);

  // the row sums, added as the CPU loop adds its own
  row_sums_.resize(2 * static_cast<size_t>(n));
  read_back(buffers_[kForces], 0, coordinates, row_sums_.data());
  for (size_t c = 0; c < row_sums_.size(); ++c) e.force[c] += row_sums_[c];
  if (e.row_max) read_back(buffers_[kRowMax], 0, static_cast<size_t>(n) * sizeof(double), e.row_max);
  if (e.breaking) {
    // the rows that broke bonds are few (a crack tip): read their stiffness and mark, as the CPU's
    // cut_row_forces does, every bond the GPU zeroed and the host still holds
    row_flags_.resize(n);
    read_back(buffers_[kRowBroke], 0, static_cast<size_t>(n) * sizeof(uint32_t), row_flags_.data());
    for (int i = 0; i < n; ++i) {
      if (row_flags_[i] == 0u) continue;
      e.row_broke[i] = 1;
      const int64_t begin = bonds.row[i], count = bonds.row[i + 1] - begin;
      row_stiffness_.resize(static_cast<size_t>(count));
      read_back(buffers_[kStiffness], static_cast<size_t>(begin) * sizeof(float),
                static_cast<size_t>(count) * sizeof(float), row_stiffness_.data());
      for (int64_t b = 0; b < count; ++b)
        if (row_stiffness_[b] == 0.0f && bonds.stiffness[begin + b] > 0.0f) bonds.broken[begin + b] = 2;
    }
  }
  check_gl("the GPU bond-force pass");
}

void GlBondForceDevice::dispatch(const Pass& pass) {
  const GLuint program = context_->bond_force_program();
  glUseProgram(program);
  for (int b = 0; b < kBufferCount; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers_[b]);
  glUniform1i(glGetUniformLocation(program, "u_count"), particles_);
  glUniform1i(glGetUniformLocation(program, "u_damped"), pass.damped ? 1 : 0);
  glUniform1d(glGetUniformLocation(program, "u_eta_over_e"), pass.eta_over_e);
  glUniform1i(glGetUniformLocation(program, "u_breaking"), pass.breaking ? 1 : 0);
  glUniform1d(glGetUniformLocation(program, "u_s0"), pass.s0);
  glUniform1i(glGetUniformLocation(program, "u_track"), pass.track ? 1 : 0);
  glUniform1i(glGetUniformLocation(program, "u_has_no_fail"), has_no_fail_ ? 1 : 0);
  // a dispatch has at most 65535 groups along an axis (the least every driver gives): larger
  // bodies take rows of groups on the second axis, the shader's row index spanning both
  const GLuint groups = static_cast<GLuint>((particles_ + kGroupSize - 1) / kGroupSize);
  const GLuint across = std::min<GLuint>(groups, groups_across_);
  glDispatchCompute(across, (groups + across - 1) / across, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

void GlBondForceDevice::repeat_last_pass() {
  if (particles_ == 0) return;
  EglContext::Scope current(context_->egl());
  dispatch(last_);
  glFinish();
  check_gl("the GPU bond-force pass");
}

BondForceDeviceFactory gl_bond_force_device_factory(const std::string& resource_root) {
  // the context is made by the first body that asks, on its thread, and shared by the others
  auto shared = std::make_shared<std::shared_ptr<GlComputeContext>>();
  auto once = std::make_shared<std::mutex>();
  return [resource_root, shared, once]() -> std::unique_ptr<BondForceDevice> {
    std::lock_guard<std::mutex> lock(*once);
    if (!*shared) *shared = std::make_shared<GlComputeContext>(resource_root);
    return std::make_unique<GlBondForceDevice>(*shared);
  };
}

std::string gl_compute_unavailable_reason(const std::string& resource_root) {
  try {
    GlComputeContext probe(resource_root);
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace periflex
