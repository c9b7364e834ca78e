// SPDX-License-Identifier: Apache-2.0
// HttpApi: what /state, /metrics and /api/... answer, from a read-only view of the daemon (DaemonStatus). Every
// change goes through SceneControl, validated by the config file's own readers; a refused change answers 400 naming the
// field and changes nothing. Loop thread only.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>

#include "control/daemon_status.h"
#include "control/scene_control.h"
#include "http/http_server.h"

namespace overlayd {

class HttpApi
{
public:
    // counters: the server's, for /state and /metrics (the server is created after the API it calls).
    HttpApi(SceneControl &scene, const DaemonStatus &status, std::function<HttpCounters()> counters);

    HttpResponse handle(const HttpRequest &request);

private:
    HttpResponse state();
    HttpResponse metrics();
    HttpResponse putCamera(const HttpRequest &request);
    HttpResponse putLayer(const std::string &layer, const HttpRequest &request);
    HttpResponse putText(const std::string &slot, const HttpRequest &request);
    HttpResponse project(const HttpRequest &request);
    HttpResponse unproject(const HttpRequest &request);
    HttpResponse save();
    double measuredFps();
    // What every part the daemon lists (sinks, GPIO, each kind of input) reports of itself, after what `report`
    // holds already.
    void addParts(StatusReport &report) const;

    SceneControl &scene_;
    const DaemonStatus &status_;
    std::function<HttpCounters()> counters_;
    const std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
    // fps measured between two samples at least a second apart
    std::chrono::steady_clock::time_point sampleTime_ = started_;
    uint64_t sampleFrames_ = 0;
    double fps_ = 0.0;
};

} // namespace overlayd
