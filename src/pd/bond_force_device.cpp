#include "pd/bond_force_device.h"

#include <mutex>
#include <stdexcept>
#include <utility>

namespace periflex {

namespace {

// the one factory of the process, set by the program before any model is built
std::mutex& factory_mutex() {
  static std::mutex m;
  return m;
}
BondForceDeviceFactory& installed_factory() {
  static BondForceDeviceFactory factory;
  return factory;
}

}  // namespace

void install_bond_force_device(BondForceDeviceFactory factory) {
  std::lock_guard<std::mutex> lock(factory_mutex());
  installed_factory() = std::move(factory);
}

bool bond_force_device_installed() {
  std::lock_guard<std::mutex> lock(factory_mutex());
  return static_cast<bool>(installed_factory());
}

const char* precision_name(DevicePrecision precision) {
  return precision == DevicePrecision::kFp32 ? "fp32" : "fp64";
}

double device_bytes_needed(double particles, double directed_bonds, DevicePrecision precision) {
  const bool fp32 = precision == DevicePrecision::kFp32;
  const double per_direction = 4.0 + 1.0 + 4.0 + (fp32 ? 8.0 : 0.0);
  const double real = fp32 ? 4.0 : 8.0;
  const double per_particle = 4.0 + 4.0 + 1.0 + 7.0 * real;
  return directed_bonds * per_direction + particles * per_particle;
}

DevicePrecision device_precision(const std::string& name) {
  return name == "fp32" ? DevicePrecision::kFp32 : DevicePrecision::kFp64;
}

std::unique_ptr<BondForceDevice> make_bond_force_device(DevicePrecision precision) {
  BondForceDeviceFactory factory;
  {
    std::lock_guard<std::mutex> lock(factory_mutex());
    factory = installed_factory();
  }
  if (!factory) throw std::runtime_error("this program was built without a GPU backend (no OpenGL compute)");
  return factory(precision);
}

}  // namespace periflex
