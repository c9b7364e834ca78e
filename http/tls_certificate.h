// SPDX-License-Identifier: Apache-2.0
// TlsCertificate: the certificate chain and key GnuTLS hands to each TLS handshake of the HTTP server. It is chosen
// per handshake (libmicrohttpd's HTTPS_CERT_CALLBACK) rather than loaded into the daemon once, so that a reload can
// put a renewed certificate in place while the open connections, MJPEG streams among them, go on.
#pragma once

#include <memory>

#include "base/result.h"
#include "http/tls_files.h"

namespace overlayd {

class TlsCertificate
{
public:
    static Result<std::unique_ptr<TlsCertificate>> create(const TlsFiles &files);
    ~TlsCertificate();
    TlsCertificate(const TlsCertificate &) = delete;
    TlsCertificate &operator=(const TlsCertificate &) = delete;

    // Serves `certificate` to the next handshakes. GnuTLS's callback carries no user pointer, so the certificate
    // in service is one per process (there is one HTTP server); the one replaced is kept until the next change, for
    // a handshake that is still using it.
    static void serve(std::unique_ptr<TlsCertificate> certificate);
    // libmicrohttpd's MHD_OPTION_HTTPS_CERT_CALLBACK (a gnutls_certificate_retrieve_function2).
    static void *callback();

    struct Parts; // GnuTLS's certificate list and key
    Parts &parts() const { return *parts_; }

private:
    TlsCertificate() = default;
    std::unique_ptr<Parts> parts_;
};

} // namespace overlayd
