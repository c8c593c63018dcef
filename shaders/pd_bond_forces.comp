#version 430 core
// Bond-based peridynamic forces of one body, fp64, one invocation per particle row: each row
// gathers its own force over its stored bond directions (both copies of a bond are stored, one in
// each row), so no two invocations write the same value and no atomics are needed. The formulas
// are the CPU's (src/pd/bond_kernel.cpp, cut_row_forces): the same stretch, bit for bit, decides
// a break in both copies of a bond. `precise` keeps the compiler from fusing them into FMAs.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer RowOffsets { uint row_offset[]; };   // n + 1
layout(std430, binding = 1) readonly buffer Neighbors { int neighbor[]; };       // j of each bond
layout(std430, binding = 2) readonly buffer LengthClasses { uint length_class[]; };  // 4 bytes a word
layout(std430, binding = 3) buffer Stiffness { float stiffness[]; };             // 0 once broken
layout(std430, binding = 4) readonly buffer InvLengths { double inv_length[]; }; // 1/|xi| per class
layout(std430, binding = 5) readonly buffer Positions { double pos[]; };         // 2n, interleaved
layout(std430, binding = 6) readonly buffer Velocities { double vel[]; };        // 2n, when damped
layout(std430, binding = 7) writeonly buffer Forces { double force[]; };         // 2n row sums
layout(std430, binding = 8) buffer RowBroke { uint row_broke[]; };               // n, 0 on entry
layout(std430, binding = 9) writeonly buffer RowMax { double row_max[]; };       // n, when tracked
layout(std430, binding = 10) readonly buffer NoFail { uint no_fail[]; };         // 4 bytes a word

uniform int u_count;         // particles
uniform int u_damped;        // 1: bond damping eta / E = u_eta_over_e
uniform double u_eta_over_e;
uniform int u_breaking;      // 1: leave out and break the breakable intact bonds past u_s0
uniform double u_s0;
uniform int u_track;         // 1: write each row's largest stretch over its intact bonds
uniform int u_has_no_fail;   // 1: no_fail holds one byte per particle

uint byte_at(uint word, uint index) { return (word >> (8u * (index & 3u))) & 255u; }
bool fixed_particle(int p) { return u_has_no_fail == 1 && byte_at(no_fail[uint(p) >> 2], uint(p)) != 0u; }

void main() {
  // rows beyond 65535 groups of 64 (4.2M particles) continue on the grid's second axis
  const int i = int(gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x);
  if (i >= u_count) return;
  const double xi = pos[2 * i], yi = pos[2 * i + 1];
  const double vxi = u_damped == 1 ? vel[2 * i] : 0.0LF, vyi = u_damped == 1 ? vel[2 * i + 1] : 0.0LF;
  const bool fixed_i = fixed_particle(i);
  double fx = 0.0LF, fy = 0.0LF, top = -1.0LF;
  bool broke = false;
  for (uint b = row_offset[i]; b < row_offset[i + 1]; ++b) {
    const int j = neighbor[b];
    precise double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
    precise double len = sqrt(dx * dx + dy * dy);
    const double l0 = inv_length[byte_at(length_class[b >> 2], b)];
    const double k = double(stiffness[b]);
    precise double s = len * l0 - 1.0LF;
    if (u_track == 1 && k > 0.0LF) top = max(top, s);
    if (u_breaking == 1 && s > u_s0 && k > 0.0LF && !fixed_i && !fixed_particle(j)) {
      // this copy breaks here; the other copy, in row j, sees the same stretch and breaks too
      stiffness[b] = 0.0;
      broke = true;
      continue;
    }
    precise double inv_len = 1.0LF / len;
    precise double f = k * (l0 - inv_len);
    if (u_damped == 1) {
      precise double dvx = vel[2 * j] - vxi, dvy = vel[2 * j + 1] - vyi;
      precise double rate = (dx * dvx + dy * dvy) * inv_len * l0;
      f = k * ((l0 - inv_len) + u_eta_over_e * rate * inv_len);
    }
    fx += f * dx;
    fy += f * dy;
  }
  force[2 * i] = fx;
  force[2 * i + 1] = fy;
  if (u_track == 1) row_max[i] = top;
  if (broke) row_broke[i] = 1u;
}
