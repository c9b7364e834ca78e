// SPDX-License-Identifier: Apache-2.0
// RtspOutput: the server's signals run on the engine's main loop thread, push() on the encoder's streaming thread;
// the mutex guards what both touch (the media's appsrc, the clients).
#include "stream/gst/rtsp_output.h"

#include <sys/socket.h>

#include <gst/app/gstappsrc.h>

namespace overlayd {
namespace {

// At most this many access units wait in a media's appsrc: a media that cannot keep up drops the oldest, never
// stalls the encoder (and the other sinks).
constexpr guint64 kMediaQueueBuffers = 30;
// Connections the kernel queues before the server accepts them: the system's largest. gst-rtsp-server's default, 5,
// makes every sixth connection of a quick succession wait for a SYN retransmit (1 s); 128 still overflowed in a storm
// while the engine's loop shared the cores with the encoder (2,000 connections: 6.2 s, against 0.2 s with this one).
// What is accepted is bounded by the pending-client caps.
constexpr gint kListenBacklog = SOMAXCONN;
static_assert(kMaxPendingRtspClients >= kMaxRtspClients, "a sink's max_clients may all connect at once");

std::string peerAddress(GstRTSPClient *client)
{
    GstRTSPConnection *connection = gst_rtsp_client_get_connection(client);
    if (connection == nullptr)
        return "?";
    std::string address = gst_rtsp_connection_get_ip(connection);
    if (GSocket *socket = gst_rtsp_connection_get_read_socket(connection)) {
        if (GSocketAddress *remote = g_socket_get_remote_address(socket, nullptr)) {
            if (G_IS_INET_SOCKET_ADDRESS(remote)) {
                const guint16 port = g_inet_socket_address_get_port(G_INET_SOCKET_ADDRESS(remote));
                address = (address.find(':') != std::string::npos ? "[" + address + "]" : address) + ":" +
                          std::to_string(port);
            }
            g_object_unref(remote);
        }
    }
    return address;
}

} // namespace

RtspOutput::RtspOutput(const EncodedSinkOptions &options, const EngineLog &log, std::function<void()> requestKeyframe)
    : options_(options), log_(log), requestKeyframe_(std::move(requestKeyframe)), access_(options, log),
      // As many as may play may connect at once from one address (a recorder opening its streams together).
      pending_(PendingClientLimits{.perAddress = options.rtsp.maxClients})
{}

RtspOutput::~RtspOutput()
{
    if (pendingTick_ != nullptr) {
        g_source_destroy(pendingTick_);
        g_source_unref(pendingTick_);
    }
    if (source_ != nullptr) {
        g_source_destroy(source_);
        g_source_unref(source_);
    }
    std::map<GstRTSPClient *, RtspClientState> clients;
    {
        std::lock_guard lock(mutex_);
        clients.swap(clients_);
    }
    for (const auto &[client, state] : clients) // no signal of theirs may reach this object once it is gone
        g_signal_handlers_disconnect_by_data(client, this), g_signal_handlers_disconnect_by_data(client, &access_);
    if (server_ != nullptr) {
        // Clients still connected are closed: their sessions hold the media.
        gst_rtsp_server_client_filter(
            server_, [](GstRTSPServer *, GstRTSPClient *, gpointer) { return GST_RTSP_FILTER_REMOVE; }, nullptr);
        g_object_unref(server_);
    }
    std::lock_guard lock(mutex_);
    if (appsrc_ != nullptr)
        gst_object_unref(appsrc_);
    if (media_ != nullptr) {
        g_signal_handlers_disconnect_by_data(media_, this);
        g_object_unref(media_);
    }
}

Status RtspOutput::start(GMainContext *context)
{
    server_ = gst_rtsp_server_new();
    gst_rtsp_server_set_address(server_, options_.rtsp.host.c_str());
    gst_rtsp_server_set_service(server_, std::to_string(options_.rtsp.port).c_str());
    gst_rtsp_server_set_backlog(server_, kListenBacklog);
    GstRTSPMediaFactory *factory = gst_rtsp_media_factory_new();
    // h264parse puts SPS/PPS before every keyframe, rtph264pay sends them with every IDR: a client may start at any.
    gst_rtsp_media_factory_set_launch(factory, "( appsrc name=encoded is-live=true format=time ! h264parse "
                                               "config-interval=-1 ! rtph264pay name=pay0 pt=96 config-interval=-1 )");
    gst_rtsp_media_factory_set_shared(factory, TRUE); // one media, one pipeline, for every client of the mount
    gst_rtsp_media_factory_set_protocols(factory,
                                         GstRTSPLowerTrans(GST_RTSP_LOWER_TRANS_UDP | GST_RTSP_LOWER_TRANS_TCP));
    g_signal_connect(factory, "media-configure", G_CALLBACK(onMediaConfigure), this);
    if (auto applied = access_.apply(server_, factory); !applied) {
        g_object_unref(factory);
        return applied;
    }
    GstRTSPMountPoints *mounts = gst_rtsp_server_get_mount_points(server_);
    gst_rtsp_mount_points_add_factory(mounts, options_.rtsp.path.c_str(), factory);
    g_object_unref(mounts);
    g_signal_connect(server_, "client-connected", G_CALLBACK(onClientConnected), this);
    // Clients are served on the engine's loop (no client thread of the pool's): RTSP requests are few and light, and
    // a client may then be closed from this loop (the pending limits) without racing its own thread.
    GstRTSPThreadPool *pool = gst_rtsp_server_get_thread_pool(server_);
    gst_rtsp_thread_pool_set_max_threads(pool, 0);
    g_object_unref(pool);

    GError *error = nullptr;
    source_ = gst_rtsp_server_create_source(server_, nullptr, &error);
    if (source_ == nullptr) {
        std::string message =
            options_.key + ": RTSP cannot listen on " + options_.rtsp.listen + ": " + (error ? error->message : "?");
        g_clear_error(&error);
        return makeError(ErrorCode::Io, message);
    }
    g_source_attach(source_, context);
    pendingTick_ = g_timeout_source_new_seconds(1);
    g_source_set_callback(pendingTick_, onPendingTick, this, nullptr);
    g_source_attach(pendingTick_, context);
    return Ok{};
}

gboolean RtspOutput::onPendingTick(gpointer data)
{
    auto *self = static_cast<RtspOutput *>(data);
    std::vector<PendingClients::Handle> late;
    {
        std::lock_guard lock(self->mutex_);
        late = self->pending_.expired(PendingClients::Clock::now());
    }
    self->closeClients(late, "did not ask to play within the deadline");
    return G_SOURCE_CONTINUE;
}

void RtspOutput::closeClients(const std::vector<PendingClients::Handle> &handles, const char *why)
{
    for (PendingClients::Handle handle : handles) {
        auto *client = static_cast<GstRTSPClient *>(const_cast<void *>(handle));
        // Debug level: a storm of hostile connections must not flood the journal (the metric counts them).
        log_(kLogDebug, options_.key + ": RTSP client " + peerAddress(client) + " closed: " + why);
        // Our own reference through the close: it drops the server's, and the client must not be finalized while
        // gst_rtsp_client_close still holds its lock (GLib aborts on clearing a locked mutex).
        g_object_ref(client);
        gst_rtsp_client_close(client);
        g_object_unref(client);
    }
}

void RtspOutput::onClientConnected(GstRTSPServer *, GstRTSPClient *client, RtspOutput *self)
{
    g_signal_connect(client, "closed", G_CALLBACK(onClientClosed), self);
    g_signal_connect(client, "pre-describe-request", G_CALLBACK(onPreDescribe), self);
    g_signal_connect(client, "setup-request", G_CALLBACK(onSetup), self);
    g_signal_connect(client, "play-request", G_CALLBACK(onPlay), self);
    const std::string address = peerAddress(client);
    self->access_.admit(client);
    GstRTSPConnection *connection = gst_rtsp_client_get_connection(client);
    const std::string host = connection != nullptr ? gst_rtsp_connection_get_ip(connection) : "?";
    std::vector<PendingClients::Handle> shed;
    {
        std::lock_guard lock(self->mutex_);
        self->clients_[client] = RtspClientState{address, "", std::chrono::system_clock::now()};
        shed = self->pending_.admit(client, host, PendingClients::Clock::now());
    }
    self->closeClients(shed, "shed for a new connection (too many have not asked to play)");
}

void RtspOutput::onClientClosed(GstRTSPClient *client, RtspOutput *self)
{
    std::lock_guard lock(self->mutex_);
    self->pending_.closed(client);
    if (auto found = self->clients_.find(client); found != self->clients_.end()) {
        self->log_(kLogInfo, self->options_.key + ": RTSP client " + found->second.address + " left");
        self->clients_.erase(found);
    }
}

GstRTSPStatusCode RtspOutput::onPreDescribe(GstRTSPClient *, GstRTSPContext *, RtspOutput *self)
{
    std::lock_guard lock(self->mutex_);
    size_t playing = 0;
    for (const auto &[client, state] : self->clients_)
        playing += state.transport.empty() ? 0 : 1;
    if (playing >= self->options_.rtsp.maxClients)
        return GST_RTSP_STS_SERVICE_UNAVAILABLE;
    return GST_RTSP_STS_OK;
}

void RtspOutput::onSetup(GstRTSPClient *client, GstRTSPContext *context, RtspOutput *self)
{
    gchar *transport = nullptr;
    if (context->request == nullptr ||
        gst_rtsp_message_get_header(context->request, GST_RTSP_HDR_TRANSPORT, &transport, 0) != GST_RTSP_OK)
        return;
    const std::string text = transport;
    const char *kind = text.find("RTP/AVP/TCP") != std::string::npos ? "tcp"
                       : text.find("multicast") != std::string::npos ? "udp-multicast"
                                                                     : "udp";
    std::lock_guard lock(self->mutex_);
    if (auto found = self->clients_.find(client); found != self->clients_.end())
        found->second.transport = kind;
}

void RtspOutput::onPlay(GstRTSPClient *client, GstRTSPContext *, RtspOutput *self)
{
    {
        std::lock_guard lock(self->mutex_);
        self->pending_.started(client);
        if (auto found = self->clients_.find(client); found != self->clients_.end())
            self->log_(kLogInfo, self->options_.key + ": RTSP client " + found->second.address + " plays over " +
                                     found->second.transport);
    }
    self->requestKeyframe_(); // a late joiner decodes from the next frame instead of the next interval
}

void RtspOutput::onMediaConfigure(GstRTSPMediaFactory *, GstRTSPMedia *media, RtspOutput *self)
{
    GstElement *bin = gst_rtsp_media_get_element(media);
    GstElement *appsrc = gst_bin_get_by_name_recurse_up(GST_BIN(bin), "encoded");
    gst_object_unref(bin);
    g_object_set(appsrc, "max-buffers", guint64(kMediaQueueBuffers), nullptr);
    gst_util_set_object_arg(G_OBJECT(appsrc), "leaky-type", "downstream");
    g_signal_connect(media, "unprepared", G_CALLBACK(onMediaUnprepared), self);
    {
        std::lock_guard lock(self->mutex_);
        if (self->appsrc_ != nullptr)
            gst_object_unref(self->appsrc_);
        self->appsrc_ = appsrc; // the reference from get_by_name
        if (self->media_ != nullptr) {
            g_signal_handlers_disconnect_by_data(self->media_, self);
            g_object_unref(self->media_);
        }
        self->media_ = GST_RTSP_MEDIA(g_object_ref(media));
        self->waitingForKeyframe_ = true;
        self->offset_ = GST_CLOCK_TIME_NONE;
    }
    self->requestKeyframe_();
}

void RtspOutput::onMediaUnprepared(GstRTSPMedia *, RtspOutput *self)
{
    std::lock_guard lock(self->mutex_);
    if (self->appsrc_ != nullptr)
        gst_object_unref(self->appsrc_);
    self->appsrc_ = nullptr;
}

bool RtspOutput::push(GstSample *sample)
{
    GstBuffer *buffer = gst_sample_get_buffer(sample);
    std::lock_guard lock(mutex_);
    if (appsrc_ == nullptr || buffer == nullptr)
        return false;
    if (waitingForKeyframe_ && GST_BUFFER_FLAG_IS_SET(buffer, GST_BUFFER_FLAG_DELTA_UNIT))
        return false; // a new media starts at a keyframe: its first client decodes from the first packet
    waitingForKeyframe_ = false;
    // The media's timeline starts at its first access unit (a keyframe: its DTS is the earliest of what follows),
    // as its running time starts when it goes to PLAYING; a time before it (cannot happen without B-frames) is 0.
    if (!GST_CLOCK_TIME_IS_VALID(offset_))
        offset_ = GST_BUFFER_DTS_IS_VALID(buffer) ? GST_BUFFER_DTS(buffer) : GST_BUFFER_PTS(buffer);
    GstBuffer *shifted = gst_buffer_copy(buffer); // the metadata only: the memory is shared
    for (GstClockTime *time : {&GST_BUFFER_PTS(shifted), &GST_BUFFER_DTS(shifted)})
        if (GST_CLOCK_TIME_IS_VALID(*time))
            *time = *time > offset_ ? *time - offset_ : 0;
    GstSample *moved = gst_sample_new(shifted, gst_sample_get_caps(sample), nullptr, nullptr);
    gst_buffer_unref(shifted);
    gst_app_src_push_sample(GST_APP_SRC(appsrc_), moved);
    gst_sample_unref(moved);
    return true;
}

EncodedSinkState RtspOutput::state() const
{
    EncodedSinkState out;
    out.kind = "rtsp";
    out.key = options_.key;
    out.describe = (access_.tls() ? "rtsps://" : "rtsp://") + options_.rtsp.listen + options_.rtsp.path;
    std::lock_guard lock(mutex_);
    for (const auto &[client, state] : clients_)
        out.clients.push_back(state);
    out.pendingShed = pending_.shed();
    out.pendingTimedOut = pending_.timedOut();
    return out;
}

} // namespace overlayd
