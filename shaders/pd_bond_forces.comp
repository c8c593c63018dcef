#version 430 core
// Bond-based peridynamic forces of one body, one invocation per particle row: each row gathers its
// own force over its stored bond directions (both copies of a bond are stored, one in each row), so
// no two invocations write the same value and no atomics are needed.
//
// Bonds are stored slot-major (bond k of row i at k * n + i): neighbouring invocations read
// neighbouring words, so each read of a group is one coalesced transaction rather than 64 scattered
// ones (the rows of a horizon of 3 spacings hold up to 28 bonds; shorter rows leave their last
// slots unread).
//
// fp64 (the default): the CPU's formulas (src/pd/bond_kernel.cpp, cut_row_forces): the same
// stretch, bit for bit, decides a break in both copies of a bond; `precise` keeps the compiler
// from fusing them into FMAs. PD_FP32 (defined by the host): the displacement form, in single
// precision throughout: `pos` holds displacements from the reference, the reference bond vectors
// are stored, and the stretch follows from 2 xi.eta + eta.eta, with no cancellation of large
// coordinates.
layout(local_size_x = 64) in;

#ifdef PD_FP32
#define real float
#define REAL(x) float(x)
#else
#define real double
#define REAL(x) double(x)
#endif

layout(std430, binding = 0) readonly buffer RowLengths { uint row_length[]; };       // n
layout(std430, binding = 1) readonly buffer Neighbors { int neighbor[]; };           // slot-major
layout(std430, binding = 2) readonly buffer LengthClasses { uint length_class[]; };  // slot-major, 4 bytes a word
layout(std430, binding = 3) buffer Stiffness { float stiffness[]; };                 // slot-major, 0 once broken
layout(std430, binding = 4) readonly buffer InvLengths { real inv_length[]; };       // 1/|xi| per class
layout(std430, binding = 5) readonly buffer Positions { real pos[]; };               // 2n, interleaved
layout(std430, binding = 6) readonly buffer Velocities { real vel[]; };              // 2n, when damped
layout(std430, binding = 7) writeonly buffer Forces { real force[]; };               // 2n row sums
layout(std430, binding = 8) writeonly buffer BrokeBits { uint broke_bits[]; };       // word w of row i at w n + i
layout(std430, binding = 9) writeonly buffer RowMax { real row_max[]; };             // n, when tracked
layout(std430, binding = 10) readonly buffer NoFail { uint no_fail[]; };             // 4 bytes a word
layout(std430, binding = 11) readonly buffer ReferenceBonds { vec2 xi_ref[]; };      // slot-major, fp32 only

uniform uint u_count;        // particles (n)
uniform uint u_words;        // words of broke_bits per row
uniform int u_damped;        // 1: bond damping eta / E = u_eta_over_e
uniform real u_eta_over_e;
uniform int u_breaking;      // 1: leave out and break the breakable intact bonds past u_s0
uniform real u_s0;
uniform int u_track;         // 1: write each row's largest stretch over its intact bonds
uniform int u_has_no_fail;   // 1: no_fail holds one byte per particle

uint byte_at(uint word, uint index) { return (word >> (8u * (index & 3u))) & 255u; }
bool fixed_particle(uint p) { return u_has_no_fail == 1 && byte_at(no_fail[p >> 2], p) != 0u; }

void main() {
  // rows beyond 65535 groups of 64 (4.2M particles) continue on the grid's second axis
  const uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  if (i >= u_count) return;
  const uint n = u_count;
  const real xi = pos[2 * i], yi = pos[2 * i + 1];
  const real vxi = u_damped == 1 ? vel[2 * i] : REAL(0), vyi = u_damped == 1 ? vel[2 * i + 1] : REAL(0);
  const bool fixed_i = fixed_particle(i);
  real fx = REAL(0), fy = REAL(0), top = REAL(-1);
  uint broke = 0u;  // the bits of the word being filled
  const uint bonds = row_length[i];
  for (uint k = 0u; k < bonds; ++k) {
    const uint b = k * n + i;
    const uint j = uint(neighbor[b]);
    const real l0 = inv_length[byte_at(length_class[b >> 2], b)];
    const float k_bond = stiffness[b];
#ifdef PD_FP32
    // the deformed bond y = xi + eta; len^2 - |xi|^2 = 2 xi.eta + eta.eta, so that
    // s = (2 xi.eta + eta.eta) l0^2 / (len l0 + 1) keeps its relative precision at small stretch
    const vec2 x0 = xi_ref[b];
    const vec2 eta = vec2(pos[2 * j] - xi, pos[2 * j + 1] - yi);
    const vec2 y = x0 + eta;
    const float len = length(y);
    const float s = (2.0 * dot(x0, eta) + dot(eta, eta)) * l0 * l0 / (len * l0 + 1.0);
    const float dx = y.x, dy = y.y;
#else
    precise double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
    precise double len = sqrt(dx * dx + dy * dy);
    precise double s = len * l0 - 1.0LF;
#endif
    if (u_track == 1 && k_bond > 0.0) top = max(top, s);
    if (u_breaking == 1 && s > u_s0 && k_bond > 0.0 && !fixed_i && !fixed_particle(j)) {
      // this copy breaks here; the other copy, in row j, sees the same stretch and breaks too
      stiffness[b] = 0.0;
      broke |= 1u << (k & 31u);
    } else {
#ifdef PD_FP32
      const float inv_len = 1.0 / len;
      float f = k_bond * s * inv_len;
      if (u_damped == 1) {
        const float rate = (dx * (vel[2 * j] - vxi) + dy * (vel[2 * j + 1] - vyi)) * inv_len * l0;
        f = k_bond * (s + u_eta_over_e * rate) * inv_len;
      }
#else
      precise double inv_len = 1.0LF / len;
      precise double f = double(k_bond) * (l0 - inv_len);
      if (u_damped == 1) {
        precise double dvx = vel[2 * j] - vxi, dvy = vel[2 * j + 1] - vyi;
        precise double rate = (dx * dvx + dy * dvy) * inv_len * l0;
        f = double(k_bond) * ((l0 - inv_len) + u_eta_over_e * rate * inv_len);
      }
#endif
      fx += f * dx;
      fy += f * dy;
    }
    // each row writes its own words only
    if (u_breaking == 1 && ((k & 31u) == 31u || k + 1u == bonds)) {
      broke_bits[(k >> 5) * n + i] = broke;
      broke = 0u;
    }
  }
  if (u_breaking == 1)
    for (uint w = (bonds + 31u) >> 5; w < u_words; ++w) broke_bits[w * n + i] = 0u;
  force[2 * i] = fx;
  force[2 * i + 1] = fy;
  if (u_track == 1) row_max[i] = top;
}
