// SPDX-License-Identifier: Apache-2.0
// [http]: the server's address, limits and control mode, checked as far as a file can be (the address parses, an
// open control API listens only locally, a unix socket's folder exists, the token file holds a token: read by the
// server's own reader); whether the port is free is known only when `run` binds it.
#include "config/config_sections.h"

#include <algorithm>

#include "http/credentials.h"
#include "http/listen_address.h"
#include "http/tls_files.h"
#include "http/token_file.h"

namespace overlayd {

void readHttp(TableReader &root, const std::string &baseDirectory, HttpOptions &out)
{
    auto table = root.table("http");
    if (!table)
        return;
    if (!httpBuiltIn()) { // refused here, so that check-config refuses what run could not do
        root.problem("http", "this overlayd was built without the HTTP server (CMake option OVERLAYD_HTTP, "
                             "libmicrohttpd): [http] is not available");
        return;
    }
    out.enabled = true;
    std::optional<ListenAddress> address;
    if (auto listen = table->string("listen")) {
        out.listen = *listen;
        if (auto parsed = parseListenAddress(*listen))
            address = *parsed;
        else
            table->problem("listen", parsed.error().message);
        if (Status folder = address ? checkListenFolder(*address) : Status(Ok{}); !folder)
            table->problem("listen", "'" + *listen + "': " + folder.error().message);
    } else {
        address = *parseListenAddress(out.listen);
    }
    if (auto clients = table->integer("max_clients", 1, kMaxClients))
        out.maxClients = unsigned(*clients);
    if (auto streams = table->integer("max_streams", 1, out.maxClients))
        out.maxStreams = unsigned(*streams);
    if (auto pending = table->integer("max_pending_per_address", 1, out.maxClients))
        out.maxPendingPerAddress = unsigned(*pending);
    if (auto fps = table->positive("stream_fps", kMaxStreamFps))
        out.streamFps = *fps;
    if (auto quality = table->integer("jpeg_quality", 1, 100))
        out.jpegQuality = int(*quality);
    if (auto control = table->choice<ControlMode>(
            "control", {{"off", ControlMode::Off}, {"token", ControlMode::Token}, {"open", ControlMode::Open}}))
        out.control = *control;
    if (out.control == ControlMode::Open && address && !address->isLocal())
        table->problem("control", "\"open\" lets anyone who can connect change the scene: only on loopback or a "
                                  "unix socket, not " +
                                      address->describe() + " (use \"token\")");
    if (auto page = table->string("page_dir"))
        out.pageDirectory = resolvePath(baseDirectory, *page);
    if (auto tokenFile = table->string("token_file"))
        out.tokenFile = resolvePath(baseDirectory, *tokenFile);
    if (auto viewerToken = table->string("viewer_token_file"))
        out.viewerTokenFile = resolvePath(baseDirectory, *viewerToken);
    if (!out.viewerTokenFile.empty())
        if (auto token = readTokenFile(out.viewerTokenFile); !token)
            table->problem("viewer_token_file", token.error().message);
    bool controlUser = false;
    if (auto users = table->string("users_file")) {
        out.usersFile = resolvePath(baseDirectory, *users);
        if (auto read = readUsersFile(out.usersFile); !read)
            table->problem("users_file", read.error().message);
        else
            controlUser = std::any_of(read->begin(), read->end(),
                                      [](const BasicUser &user) { return user.role == Role::Control; });
    }
    // Watching needs a credential once one for viewers exists, unless the file says otherwise.
    out.viewerOpen = out.viewerTokenFile.empty() && out.usersFile.empty();
    if (auto viewer = table->choice<bool>("viewer", {{"open", true}, {"credential", false}}))
        out.viewerOpen = *viewer;
    if (out.control == ControlMode::Token) {
        if (out.tokenFile.empty()) {
            if (!controlUser)
                table->problem("token_file", "missing: control = \"token\" needs the file that holds the token (or "
                                             "a control user in users_file)");
        } else if (auto token = readTokenFile(out.tokenFile); !token) {
            table->problem("token_file", token.error().message); // what the server would refuse when it starts
        }
    }
    if (auto cert = table->string("tls_cert"))
        out.tlsCert = resolvePath(baseDirectory, *cert);
    if (auto key = table->string("tls_key"))
        out.tlsKey = resolvePath(baseDirectory, *key);
    if (out.tlsCert.empty() != out.tlsKey.empty())
        table->problem(out.tlsCert.empty() ? "tls_cert" : "tls_key",
                       "missing: HTTPS needs both tls_cert (the certificate chain) and tls_key (its private key)");
    else if (!out.tlsCert.empty()) {
        if (auto files = readTlsFiles(out.tlsCert, out.tlsKey))
            out.tls = std::move(*files);
        else
            table->problem("tls_cert", files.error().message);
    }
    table->finish();
}

} // namespace overlayd
