// SPDX-License-Identifier: Apache-2.0
// The server's certificate chain and private key (PEM), read by the config loader, so that check-config refuses
// what the server would, and so that a reload sees a renewed certificate as a changed [http] (the files' contents
// are part of HttpOptions; the server swaps them in without closing a connection).
#pragma once

#include <string>

#include "base/result.h"

namespace overlayd {

inline constexpr size_t kMaxPemBytes = 256 * 1024; // a certificate chain or key file

struct TlsFiles {
    std::string certPem; // the server's certificate first, then its intermediates
    std::string keyPem;
    bool empty() const { return certPem.empty(); }
    bool operator==(const TlsFiles &) const = default;
};

// Both files readable regular files within kMaxPemBytes, parsed by GnuTLS, and the key the certificate's. The error
// names the file (never its contents) and not the key: the caller says which.
Result<TlsFiles> readTlsFiles(const std::string &certPath, const std::string &keyPath);

} // namespace overlayd
