#include "renderer/visibility/embree_device.h"

#include <utility>

#include "scene/error.h"

namespace clipblur {

const char* embreeErrorName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_UNKNOWN: return "unknown error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unrecognised error";
}

EmbreeDevice::EmbreeDevice(const char* config) : log_(std::make_unique<ErrorLog>()) {
    device_ = rtcNewDevice(config);
    if (!device_) {
        const RTCError code = rtcGetDeviceError(nullptr);
        throw Error(ExitCode::Render, std::string("cannot create Embree device: ") + embreeErrorName(code));
    }
    rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, log_.get());
}

EmbreeDevice::~EmbreeDevice() {
    if (device_) rtcReleaseDevice(device_);
}

EmbreeDevice::EmbreeDevice(EmbreeDevice&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)), log_(std::move(other.log_)) {}

EmbreeDevice& EmbreeDevice::operator=(EmbreeDevice&& other) noexcept {
    if (this != &other) {
        if (device_) rtcReleaseDevice(device_);
        device_ = std::exchange(other.device_, nullptr);
        log_ = std::move(other.log_);
    }
    return *this;
}

void EmbreeDevice::onError(void* user, RTCError code, const char* message) {
    auto* log = static_cast<ErrorLog*>(user);
    std::lock_guard lock(log->mutex);
    if (log->code != RTC_ERROR_NONE) return;  // keep the first error: later ones are usually consequences
    log->code = code;
    log->message = message ? message : "";
}

void EmbreeDevice::check(const std::string& what) const {
    RTCError code = RTC_ERROR_NONE;
    std::string message;
    {
        std::lock_guard lock(log_->mutex);
        code = std::exchange(log_->code, RTC_ERROR_NONE);
        message = std::move(log_->message);
        log_->message.clear();
    }
    // rtcGetDeviceError also clears Embree's own sticky code; read it even when the callback fired.
    const RTCError sticky = rtcGetDeviceError(device_);
    if (code == RTC_ERROR_NONE) code = sticky;
    if (code == RTC_ERROR_NONE) return;
    std::string text = "Embree error while " + what + ": " + embreeErrorName(code);
    if (!message.empty()) text += " (" + message + ")";
    throw Error(ExitCode::Render, text);
}

}  // namespace clipblur
