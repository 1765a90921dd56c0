// device_system.hpp in a build without CUDA: no device, and a DeviceSystem is never made
// (gpu_stepper.cpp asks unavailable_reason() first).
#include "pedesis/gpu/device_system.hpp"

#include <stdexcept>

namespace pedesis::gpu {

bool cuda_built() {
    return false;
}
std::string unavailable_reason() {
    return "this pedesis was built without CUDA";
}
std::string device_description() {
    return "no CUDA device (built without CUDA)";
}

struct DeviceSystem::Impl {};

DeviceSystem::DeviceSystem(const Model&) {
    throw std::logic_error("gpu: this pedesis was built without CUDA");
}
DeviceSystem::~DeviceSystem() = default;
void DeviceSystem::upload(const HostArrays&, const double*) {}
void DeviceSystem::download(const HostArrays&) const {}
bool DeviceSystem::download_reference(double*) const {
    return false;
}
void DeviceSystem::set_coefficients(const StepCoefficients&) {}
StepStatus DeviceSystem::prestep(std::uint32_t) {
    return {};
}
bool DeviceSystem::compute_forces() {
    return false;
}
StepStatus DeviceSystem::poststep(std::uint32_t) {
    return {};
}
Totals DeviceSystem::totals() {
    return {};
}
std::size_t DeviceSystem::device_bytes() const {
    return 0;
}

} // namespace pedesis::gpu
