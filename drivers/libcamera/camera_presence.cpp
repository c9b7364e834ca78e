// SPDX-License-Identifier: Apache-2.0
// CameraPresence: the re-acquire decisions, free of libcamera types so that they are tested without a camera.
#include "drivers/libcamera/camera_presence.h"

namespace overlayd {

namespace {

bool isIndex(const std::string &spec)
{
    return !spec.empty() && spec.size() < 4 && spec.find_first_not_of("0123456789") == std::string::npos;
}

} // namespace

std::optional<size_t> matchCameraSpec(const std::string &spec, const std::vector<CameraIdentity> &present)
{
    const bool index = isIndex(spec);
    if (index && std::stoul(spec) < present.size())
        return std::stoul(spec);
    for (size_t i = 0; i < present.size(); ++i) {
        if (present[i].id == spec)
            return i;
    }
    for (size_t i = 0; i < present.size(); ++i) {
        if (!index && present[i].model.find(spec) != std::string::npos)
            return i;
    }
    return std::nullopt;
}

bool CameraPresence::isIndexSpec() const
{
    return isIndex(spec_);
}

bool CameraPresence::isRemembered(const std::string &id, const std::string &model) const
{
    if (!remembered_)
        return false;
    return id == remembered_->id || (isIndexSpec() && !model.empty() && model == remembered_->model);
}

void CameraPresence::opened(const CameraIdentity &camera)
{
    remembered_ = camera;
    state_ = State::Streaming;
    cameBack_ = false;
}

void CameraPresence::closed()
{
    if (state_ == State::Streaming)
        state_ = State::Closed;
}

void CameraPresence::apply(const CameraEvent &event)
{
    switch (event.kind) {
    case CameraEvent::Kind::Disconnected:
        // Camera::disconnected is connected on the open camera only: it names no other.
        if (state_ == State::Streaming)
            state_ = State::Gone;
        break;
    case CameraEvent::Kind::Removed:
        if (state_ == State::Streaming && remembered_ && event.cameraId == remembered_->id)
            state_ = State::Gone;
        break;
    case CameraEvent::Kind::Added:
        if (state_ == State::Gone && isRemembered(event.cameraId, event.model))
            cameBack_ = true;
        break;
    }
}

std::optional<size_t> CameraPresence::choose(const std::vector<CameraIdentity> &present) const
{
    if (!remembered_)
        return matchCameraSpec(spec_, present);
    for (size_t i = 0; i < present.size(); ++i) {
        if (present[i].id == remembered_->id)
            return i;
    }
    if (isIndexSpec()) {
        for (size_t i = 0; i < present.size(); ++i) {
            if (isRemembered(present[i].id, present[i].model))
                return i;
        }
        return std::nullopt;
    }
    // An id or a model substring names the camera by itself.
    return matchCameraSpec(spec_, present);
}

std::string CameraPresence::awaited() const
{
    if (!remembered_)
        return "\"" + spec_ + "\"";
    return "'" + remembered_->model + "' (" + remembered_->id + ")";
}

} // namespace overlayd