// SPDX-License-Identifier: Apache-2.0
// GstStreamEngine: build() makes the encoder pipeline and the RTSP servers; push() wraps a feed slot in a buffer
// whose release gives the slot back; onEncoded() counts and hands each access unit to every encoded sink.
#include "stream/gst/gst_stream_engine.h"

#include <gst/allocators/gstdmabuf.h>
#include <gst/app/gstappsrc.h>
#include <gst/video/video.h>
#include <unistd.h>

#include <cmath>

#include "stream/gst/encoder_element.h"
#include "stream/gst/file_output.h"
#include "stream/gst/push_output.h"
#include "stream/gst/record_output.h"

namespace overlayd {
namespace {

// The caps' colorimetry of the frames' matrix and range, with the transfer and primaries that go with each. Without
// it GStreamer assumes BT.709 from 720 lines, and the muxers write that into the recordings' colour atoms, so a
// player would decode a BT.601 camera's colours with the wrong matrix.
std::string capsColorimetry(const Colorimetry &colorimetry)
{
    const bool bt709 = colorimetry.matrix == YcbcrMatrix::Bt709;
    GstVideoColorimetry caps{};
    caps.range = colorimetry.range == ColourRange::Full ? GST_VIDEO_COLOR_RANGE_0_255 : GST_VIDEO_COLOR_RANGE_16_235;
    caps.matrix = bt709 ? GST_VIDEO_COLOR_MATRIX_BT709 : GST_VIDEO_COLOR_MATRIX_BT601;
    caps.transfer = bt709 ? GST_VIDEO_TRANSFER_BT709 : GST_VIDEO_TRANSFER_BT601;
    caps.primaries = bt709 ? GST_VIDEO_COLOR_PRIMARIES_BT709 : GST_VIDEO_COLOR_PRIMARIES_SMPTE170M;
    gchar *text = gst_video_colorimetry_to_string(&caps);
    std::string out = text ? text : "";
    g_free(text);
    return out;
}

// Frames whose blend time is kept for the encoded and sent stages: more than the encoder ever holds.
constexpr size_t kMaxTracked = 64;

GstClockTime nowNs()
{
    return GstClockTime(g_get_monotonic_time()) * 1000;
}

void deleteInput(gpointer input)
{
    delete static_cast<EncoderInput *>(input);
}

// The capture buffer's DMABUF as a buffer the V4L2 encoder imports (no copy), its planes placed by a video meta.
// The memory does not close the fd (the source's); its last unref deletes `held`, which gives the lease back.
GstBuffer *wrapDmabuf(GstAllocator *allocator, EncoderInput *held, const EngineFormat &format)
{
    const off_t size = lseek(held->dmabuf.fd, 0, SEEK_END); // a DMABUF's size (its fd has no other use of offsets)
    // The frame's bytes end with its last plane. The memory is cut to them: GStreamer queues its size as the
    // buffer's bytesused, and a driver refuses more than its own image size (vb2 QBUF: EINVAL), while the buffer
    // itself is rounded up to whole pages.
    const size_t frameBytes = held->dmabuf.offsets[2] + size_t(held->dmabuf.strides[2]) * ((format.height + 1) / 2);
    if (size <= 0 || frameBytes > size_t(size)) {
        delete held;
        return nullptr;
    }
    GstMemory *memory =
        gst_dmabuf_allocator_alloc_with_flags(allocator, held->dmabuf.fd, gsize(size), GST_FD_MEMORY_FLAG_DONT_CLOSE);
    gst_memory_resize(memory, 0, frameBytes);
    static const GQuark quark = g_quark_from_static_string("overlayd-encoder-input");
    gst_mini_object_set_qdata(GST_MINI_OBJECT(memory), quark, held, &deleteInput);
    GstBuffer *buffer = gst_buffer_new();
    gst_buffer_append_memory(buffer, memory);
    gsize offsets[GST_VIDEO_MAX_PLANES]{};
    gint strides[GST_VIDEO_MAX_PLANES]{};
    for (unsigned p = 0; p < 3; ++p)
        offsets[p] = held->dmabuf.offsets[p], strides[p] = gint(held->dmabuf.strides[p]);
    gst_buffer_add_video_meta_full(buffer, GST_VIDEO_FRAME_FLAG_NONE, GST_VIDEO_FORMAT_I420, format.width,
                                   format.height, 3, offsets, strides);
    return buffer;
}

} // namespace

GstStreamEngine::GstStreamEngine(const StreamOptions &options, const EngineLog &log) : options_(options), log_(log)
{
    if (options_.webrtc.enabled)
        webrtc_ = std::make_unique<WebrtcPeers>(options_.webrtc, log_, [this] { requestKeyframe(); });
}

GstStreamEngine::~GstStreamEngine()
{
    close();
    if (dmabufAllocator_ != nullptr)
        gst_object_unref(dmabufAllocator_);
}

Status GstStreamEngine::open(const EngineFormat &format)
{
    close();
    context_ = g_main_context_new();
    loop_ = g_main_loop_new(context_, FALSE);
    if (auto built = build(format); !built) {
        close();
        return built;
    }
    thread_ = std::thread([this] {
        g_main_context_push_thread_default(context_);
        g_main_loop_run(loop_);
        g_main_context_pop_thread_default(context_);
    });
    if (gst_element_set_state(pipeline_, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE) {
        close();
        return makeError(ErrorCode::Unsupported, "the encoder pipeline does not start");
    }
    if (webrtc_)
        webrtc_->start(context_);
    std::lock_guard lock(mutex_);
    state_.running = true;
    return Ok{};
}

Status GstStreamEngine::build(const EngineFormat &format)
{
    format_ = format;
    firstCapture_.reset();
    nextKeyframe_ = 0;
    auto encoder = makeEncoderElement(options_.encoder, format.fps);
    if (!encoder)
        return encoder.error();
    if (encoder->factory == "openh264enc" && options_.encoder.profile != Profile::Baseline)
        log_(kLogNotice, std::string("openh264 encodes constrained baseline only: profile = \"") +
                             profileName(options_.encoder.profile) + "\" is not used");
    pipeline_ = gst_pipeline_new("overlayd-encoder");
    appsrc_ = gst_element_factory_make("appsrc", "feed");
    GstElement *filter = gst_element_factory_make("capsfilter", nullptr);
    // FWHT frames leave vicodec whole, one per buffer, each with its header: nothing to parse.
    const bool h264 = options_.encoder.codec == Codec::H264;
    GstElement *parse = gst_element_factory_make(h264 ? "h264parse" : "identity", nullptr);
    GstElement *tee = gst_element_factory_make("tee", "encoded");
    GstElement *queue = gst_element_factory_make("queue", nullptr);
    GstElement *sink = gst_element_factory_make("appsink", "rtsp");
    if (!appsrc_ || !filter || !parse || !tee || !queue || !sink) {
        for (GstElement *element : {appsrc_, filter, parse, tee, queue, sink, encoder->element})
            if (element)
                gst_object_unref(gst_object_ref_sink(element));
        gst_object_unref(pipeline_), pipeline_ = nullptr, appsrc_ = nullptr;
        if (encoder->outputCaps)
            gst_caps_unref(encoder->outputCaps);
        return makeError(ErrorCode::NotFound, "GStreamer's appsrc, capsfilter, h264parse, tee, queue or appsink is "
                                              "missing (Debian: gstreamer1.0-plugins-base, -good, -bad)");
    }
    encoder_ = encoder->element;
    // Zero copy: the V4L2 encoder queues the capture buffers' DMABUF on its OUTPUT queue instead of copying each
    // frame into buffers of its own (a software encoder is fed copies: the daemon asks state().dmabufImport).
    const bool import = format.dmabuf && encoder->factory.starts_with("v4l2");
    if (import) {
        gst_util_set_object_arg(G_OBJECT(encoder_), "output-io-mode", "dmabuf-import");
        if (dmabufAllocator_ == nullptr)
            dmabufAllocator_ = gst_dmabuf_allocator_new();
    }
    {
        std::lock_guard lock(mutex_);
        state_ = EngineState{};
        state_.encoder = encoder->factory;
        state_.device = encoder->device;
        state_.dmabufImport = import;
    }
    const int fpsNum = format.fps > 0 ? int(std::lround(format.fps * 1000)) : 30000;
    GstCaps *raw = gst_caps_new_simple("video/x-raw", "format", G_TYPE_STRING, "I420", "width", G_TYPE_INT,
                                       int(format.width), "height", G_TYPE_INT, int(format.height), "framerate",
                                       GST_TYPE_FRACTION, fpsNum, 1000, nullptr);
    // A V4L2 encoder's sink caps list the interlacing and the colorimetries the driver takes, and its accept-caps
    // wants ours to be a subset: without the two fields vicodec refused the frames (not-negotiated). They say
    // what GStreamer assumes when they are missing: progressive, BT.601 below 720 lines, BT.709 from there.
    if (encoder->factory.starts_with("v4l2"))
        gst_caps_set_simple(raw, "interlace-mode", G_TYPE_STRING, "progressive", "colorimetry", G_TYPE_STRING,
                            format.height >= 720 ? "bt709" : "bt601", nullptr);
    else // the software encoders take any: the frames' own
        gst_caps_set_simple(raw, "colorimetry", G_TYPE_STRING, capsColorimetry(format.colorimetry).c_str(), nullptr);
    // Live and unbounded here: the feed's slots bound what waits (every queued buffer holds one).
    g_object_set(appsrc_, "caps", raw, "is-live", TRUE, "format", GST_FORMAT_TIME, "block", FALSE, nullptr);
    gst_caps_unref(raw);
    if (encoder->outputCaps) {
        g_object_set(filter, "caps", encoder->outputCaps, nullptr);
        gst_caps_unref(encoder->outputCaps);
    }
    GstCaps *au = gst_caps_from_string(h264 ? "video/x-h264,stream-format=byte-stream,alignment=au" : "video/x-fwht");
    g_object_set(sink, "caps", au, "sync", FALSE, "max-buffers", 4u, "drop", TRUE, nullptr);
    gst_caps_unref(au);
    if (h264)
        g_object_set(parse, "config-interval", -1, nullptr);
    g_object_set(tee, "allow-not-linked", TRUE, nullptr);
    GstAppSinkCallbacks callbacks{};
    callbacks.new_sample = &GstStreamEngine::onEncoded;
    gst_app_sink_set_callbacks(GST_APP_SINK(sink), &callbacks, this, nullptr);
    gst_bin_add_many(GST_BIN(pipeline_), appsrc_, encoder_, filter, parse, tee, queue, sink, nullptr);
    if (!gst_element_link_many(appsrc_, encoder_, filter, parse, tee, queue, sink, nullptr))
        return makeError(ErrorCode::Unsupported, "the encoder " + encoder->factory + " does not take " +
                                                     std::to_string(format.width) + "x" +
                                                     std::to_string(format.height) + " I420 frames");
    GstBus *bus = gst_element_get_bus(pipeline_);
    busWatch_ = gst_bus_create_watch(bus);
    g_source_set_callback(busWatch_, G_SOURCE_FUNC(&GstStreamEngine::onBusMessage), this, nullptr);
    g_source_attach(busWatch_, context_);
    gst_object_unref(bus);

    for (const EncodedSinkOptions &sinkOptions : options_.sinks) {
        if (sinkOptions.kind != EncodedSinkKind::Rtsp) {
            std::unique_ptr<EncodedOutput> output;
            if (sinkOptions.kind == EncodedSinkKind::Record)
                output = std::make_unique<RecordOutput>(sinkOptions, options_.encoder.keyframeIntervalSec, log_,
                                                        [this] { requestKeyframe(); });
            else if (sinkOptions.kind == EncodedSinkKind::File)
                output = std::make_unique<FileOutput>(sinkOptions, options_.encoder.codec, log_,
                                                      [this] { requestKeyframe(); });
            else
                output = std::make_unique<PushOutput>(sinkOptions, log_, [this] { requestKeyframe(); });
            if (auto started = output->start(context_); !started)
                return started;
            if (sinkOptions.kind == EncodedSinkKind::File)
                log_(kLogInfo, sinkOptions.key + ": " + codecName(options_.encoder.codec) + " to " +
                                   sinkOptions.file.path + " (" + encoder->factory +
                                   (encoder->device.empty() ? "" : " on " + encoder->device) + ")");
            outputs_.push_back(std::move(output));
            continue;
        }
        auto output = std::make_unique<RtspOutput>(sinkOptions, log_, [this] { requestKeyframe(); });
        if (auto started = output->start(context_); !started)
            return started;
        const char *access = sinkOptions.rtsp.access.users.empty() ? "" : ", a credential asked";
        log_(kLogInfo, sinkOptions.key + ": RTSP at " + output->state().describe + access + " (" + encoder->factory +
                           (encoder->device.empty() ? "" : " on " + encoder->device) + ")");
        rtsp_.push_back(std::move(output));
    }
    return Ok{};
}

void GstStreamEngine::push(EncoderInput frame)
{
    if (appsrc_ == nullptr)
        return; // dropped with its slot
    if (!firstCapture_)
        firstCapture_ = frame.captureTime;
    const GstClockTime now = nowNs();
    const GstClockTime pts = GstClockTime((frame.captureTime - *firstCapture_).count());
    const auto data = const_cast<uint8_t *>(frame.data);
    const size_t size = frame.size;
    // The buffer wraps the slot (or the capture buffer): GStreamer's last unref deletes the EncoderInput, which gives
    // the slot (the lease) back.
    auto *held = new EncoderInput(std::move(frame));
    GstBuffer *buffer = nullptr;
    if (held->dmabuf.fd < 0)
        buffer = gst_buffer_new_wrapped_full(GST_MEMORY_FLAG_READONLY, data, size, 0, size, held, &deleteInput);
    else if (dmabufAllocator_ != nullptr)
        buffer = wrapDmabuf(dmabufAllocator_, held, format_);
    else
        deleteInput(held); // not opened for DMABUF: the lease goes back
    if (buffer == nullptr)
        return;
    GST_BUFFER_PTS(buffer) = pts;
    GST_BUFFER_DTS(buffer) = GST_CLOCK_TIME_NONE;
    GST_BUFFER_OFFSET(buffer) = held->sequence;
    // Keyframes by time, not by frame count: when frames are dropped or a source runs slow, a count of frames
    // spans more than keyframe_s, and recordings cut at keyframes would come out short. On a grid from the first
    // frame, each on the first frame at or past its point: late frames do not push the later keyframes back, so a
    // recording's segments stay segment_s long.
    if (pts >= nextKeyframe_) {
        if (pts > 0) // the first frame is a keyframe anyway
            requestKeyframe(pts);
        const auto interval = GstClockTime(options_.encoder.keyframeIntervalSec * GST_SECOND);
        while (nextKeyframe_ <= pts)
            nextKeyframe_ += interval;
    }
    const auto blended = GstClockTime(held->blendedTime.count()); // `held` may be gone once the buffer is pushed
    if (gst_app_src_push_buffer(GST_APP_SRC(appsrc_), buffer) != GST_FLOW_OK) // takes the buffer either way
        return;
    std::lock_guard lock(mutex_);
    ++state_.framesIn;
    if (blended > 0 && now >= blended)
        encoderIn_.add(double(now - blended) / GST_SECOND);
    blendedAt_.emplace_back(pts, blended);
    while (blendedAt_.size() > kMaxTracked)
        blendedAt_.pop_front();
}

void GstStreamEngine::requestKeyframe(GstClockTime at)
{
    if (encoder_ == nullptr)
        return;
    GstPad *pad = gst_element_get_static_pad(encoder_, "src");
    gst_pad_send_event(pad, gst_video_event_new_upstream_force_key_unit(at, TRUE, 0));
    gst_object_unref(pad);
}

GstFlowReturn GstStreamEngine::onEncoded(GstAppSink *sink, gpointer data)
{
    auto *self = static_cast<GstStreamEngine *>(data);
    GstSample *sample = gst_app_sink_pull_sample(sink);
    if (sample == nullptr)
        return GST_FLOW_EOS;
    GstClockTime captured = 0; // CLOCK_MONOTONIC, ns: when the frame's overlay was blended
    if (GstBuffer *buffer = gst_sample_get_buffer(sample)) {
        const size_t bytes = gst_buffer_get_size(buffer);
        const GstClockTime now = nowNs();
        std::lock_guard lock(self->mutex_);
        ++self->state_.framesEncoded;
        self->state_.bytesEncoded += bytes;
        self->state_.keyframes += GST_BUFFER_FLAG_IS_SET(buffer, GST_BUFFER_FLAG_DELTA_UNIT) ? 0 : 1;
        self->lastSecond_.emplace_back(now, bytes);
        while (!self->lastSecond_.empty() && self->lastSecond_.front().first + GST_SECOND < now)
            self->lastSecond_.pop_front();
        for (const auto &[pts, blended] : self->blendedAt_) // the frame's blend time, by its PTS
            if (GST_BUFFER_PTS(buffer) == pts)
                captured = blended;
        if (captured > 0 && now >= captured)
            self->encoded_.add(double(now - captured) / GST_SECOND);
    }
    bool sent = false;
    for (const auto &output : self->rtsp_)
        sent = output->push(sample) || sent;
    const GstClockTime sentAt = nowNs();
    // WebRTC after RTSP: its peers' feeds queue the access unit for their own threads (payloader and DTLS-SRTP).
    const bool toPeers = self->webrtc_ && self->webrtc_->push(sample);
    const GstClockTime peersAt = nowNs();
    for (const auto &output : self->outputs_) // record and push: not a viewer's latency
        output->push(sample);
    if (captured > 0 && (sent || toPeers)) {
        std::lock_guard lock(self->mutex_);
        if (sent && sentAt >= captured)
            self->sent_.add(double(sentAt - captured) / GST_SECOND);
        if (toPeers && peersAt >= captured)
            self->webrtcSent_.add(double(peersAt - captured) / GST_SECOND);
    }
    gst_sample_unref(sample);
    return GST_FLOW_OK;
}

gboolean GstStreamEngine::onBusMessage(GstBus *, GstMessage *message, gpointer data)
{
    auto *self = static_cast<GstStreamEngine *>(data);
    if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR) {
        GError *error = nullptr;
        gchar *debug = nullptr;
        gst_message_parse_error(message, &error, &debug);
        self->log_(kLogError, std::string("encoder: ") + (error ? error->message : "?") +
                                  (debug ? std::string(" (") + debug + ")" : ""));
        g_clear_error(&error);
        g_free(debug);
        std::lock_guard lock(self->mutex_);
        self->state_.running = false;
    }
    return G_SOURCE_CONTINUE;
}

void GstStreamEngine::close()
{
    if (pipeline_ != nullptr) // every buffer GStreamer holds is dropped here: the feed gets its slots back
        gst_element_set_state(pipeline_, GST_STATE_NULL);
    if (loop_ != nullptr)
        g_main_loop_quit(loop_);
    if (thread_.joinable())
        thread_.join();
    rtsp_.clear(); // with the loop stopped: no server signal runs while the outputs go
    outputs_.clear();
    if (webrtc_)
        webrtc_->stop();
    if (busWatch_ != nullptr) {
        g_source_destroy(busWatch_);
        g_source_unref(busWatch_);
        busWatch_ = nullptr;
    }
    if (pipeline_ != nullptr)
        gst_object_unref(pipeline_);
    pipeline_ = appsrc_ = encoder_ = nullptr;
    if (loop_ != nullptr)
        g_main_loop_unref(loop_);
    if (context_ != nullptr)
        g_main_context_unref(context_);
    loop_ = nullptr, context_ = nullptr;
    std::lock_guard lock(mutex_);
    state_.running = false;
    lastSecond_.clear();
    encoderIn_ = encoded_ = sent_ = webrtcSent_ = LatencyHistogram{};
    blendedAt_.clear();
}

EngineState GstStreamEngine::state() const
{
    EngineState out;
    {
        std::lock_guard lock(mutex_);
        out = state_;
        size_t bytes = 0;
        for (const auto &[when, size] : lastSecond_)
            bytes += size;
        out.bitrateKbps = double(bytes) * 8 / 1000;
        out.latency = {{"encoder_in", encoderIn_}, {"encoded", encoded_}, {"sent", sent_}};
        if (webrtc_)
            out.latency.emplace_back("webrtc_sent", webrtcSent_);
    }
    for (const auto &output : rtsp_)
        out.sinks.push_back(output->state());
    for (const auto &output : outputs_)
        out.sinks.push_back(output->state());
    if (webrtc_)
        out.sinks.push_back(webrtc_->state());
    return out;
}

Result<WebrtcAnswer> GstStreamEngine::addPeer(const std::string &offer, const std::string &address)
{
    if (!webrtc_)
        return EncodedStreamEngine::addPeer(offer, address);
    return webrtc_->add(offer, address);
}

Status GstStreamEngine::removePeer(const std::string &id)
{
    if (!webrtc_)
        return EncodedStreamEngine::removePeer(id);
    return webrtc_->remove(id);
}

} // namespace overlayd
