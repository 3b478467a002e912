#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <embree3/rtcore.h>

namespace clipblur {

// Owns one RTCDevice. Embree reports errors through a C callback, from which an exception must not
// escape, so the callback records the first error and check() turns it into clipblur::Error
// (ExitCode::Render) on the calling side.
class EmbreeDevice {
public:
    explicit EmbreeDevice(const char* config = nullptr);
    ~EmbreeDevice();
    EmbreeDevice(EmbreeDevice&& other) noexcept;
    EmbreeDevice& operator=(EmbreeDevice&& other) noexcept;
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;

    RTCDevice get() const { return device_; }

    // Throws if the callback recorded an error or rtcGetDeviceError reports one; `what` names the step.
    void check(const std::string& what) const;

private:
    struct ErrorLog {
        std::mutex mutex;
        RTCError code = RTC_ERROR_NONE;
        std::string message;
    };
    static void onError(void* user, RTCError code, const char* message);

    RTCDevice device_ = nullptr;
    std::unique_ptr<ErrorLog> log_;  // stable address for the callback's user pointer across moves
};

const char* embreeErrorName(RTCError code);

}  // namespace clipblur
