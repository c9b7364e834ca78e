// SPDX-License-Identifier: Apache-2.0
// CameraPresence: whether the configured libcamera camera is there, and which camera to open again when it returns.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "drivers/libcamera/camera_event_queue.h"

namespace overlayd {

// A camera as the choice needs it: libcamera's id and the sensor's model.
struct CameraIdentity {
    std::string id, model;
};

// The index, id or model substring a config names, resolved against the cameras present (findCamera's rules):
// an index ("0") counts in libcamera's list, otherwise an exact id wins over a model substring.
std::optional<size_t> matchCameraSpec(const std::string &spec, const std::vector<CameraIdentity> &present);

// The re-acquire state machine, run on the daemon's loop only (the events arrive through CameraEventQueue).
//   Closed --opened()--> Streaming --Disconnected/Removed of that camera--> Gone --closed()--> Gone (waiting)
//   Gone --Added of the remembered camera--> cameBack(); the next choose() finds it and opened() streams again.
// After the first open the camera is remembered: a retry opens the same id, or, when the config names an index
// ("0"), a camera of the same model; never another camera that happens to be first in the list meanwhile.
class CameraPresence
{
public:
    enum class State { Closed, Streaming, Gone };

    explicit CameraPresence(std::string spec) : spec_(std::move(spec)) {}

    void opened(const CameraIdentity &camera);
    // The camera an earlier source of the same spec opened in this process: the daemon makes a new source for every
    // retry, and the retry must open the camera that went away, as if this presence had opened it.
    void remember(const CameraIdentity &camera) { remembered_ = camera; }
    // The source stopped on its own account (not a loss): a later open chooses by the spec again.
    void closed();
    void apply(const CameraEvent &event);

    State state() const { return state_; }
    // The open camera went away: the source reports DeviceLost and must be stopped (on the loop).
    bool lost() const { return state_ == State::Gone; }
    // An arrival of the remembered camera was seen since it went away.
    bool cameBack() const { return cameBack_; }
    const std::optional<CameraIdentity> &remembered() const { return remembered_; }

    // The camera to open among those present, or nullopt (the error then says what is awaited).
    std::optional<size_t> choose(const std::vector<CameraIdentity> &present) const;
    // "'Sensor B' (platform/vimc.0 Sensor B)" once one was opened, else the spec.
    std::string awaited() const;

private:
    bool isIndexSpec() const;
    bool isRemembered(const std::string &id, const std::string &model) const;

    std::string spec_;
    State state_ = State::Closed;
    std::optional<CameraIdentity> remembered_;
    bool cameBack_ = false;
};

} // namespace overlayd