// SPDX-License-Identifier: Apache-2.0
// readTlsFiles: the one reader of http.tls_cert and http.tls_key, checked by GnuTLS as the server will load them.
#include "http/tls_files.h"

#include <gnutls/gnutls.h>
#include <memory>
#include <type_traits>

#include "base/regular_file.h"

namespace overlayd {

namespace {

Result<std::string> readPem(const std::string &path)
{
    auto text = readRegularFile(path, kMaxPemBytes);
    if (!text)
        return makeError(text.error().code, "cannot read '" + path + "': " + text.error().message);
    return text;
}

struct CredentialsFree {
    void operator()(gnutls_certificate_credentials_t c) const { gnutls_certificate_free_credentials(c); }
};

gnutls_datum_t datum(const std::string &text)
{
    return {reinterpret_cast<unsigned char *>(const_cast<char *>(text.data())), unsigned(text.size())};
}

} // namespace

Result<TlsFiles> readTlsFiles(const std::string &certPath, const std::string &keyPath)
{
    auto cert = readPem(certPath);
    if (!cert)
        return cert.error();
    auto key = readPem(keyPath);
    if (!key)
        return key.error();
    gnutls_certificate_credentials_t raw = nullptr;
    if (gnutls_certificate_allocate_credentials(&raw) < 0)
        return makeError(ErrorCode::Io, "GnuTLS could not allocate credentials");
    std::unique_ptr<std::remove_pointer_t<gnutls_certificate_credentials_t>, CredentialsFree> credentials(raw);
    // GnuTLS parses both and refuses a key that is not the certificate's (GNUTLS_E_CERTIFICATE_KEY_MISMATCH).
    const gnutls_datum_t certDatum = datum(*cert), keyDatum = datum(*key);
    const int loaded =
        gnutls_certificate_set_x509_key_mem2(credentials.get(), &certDatum, &keyDatum, GNUTLS_X509_FMT_PEM, nullptr, 0);
    if (loaded < 0)
        return makeError(ErrorCode::InvalidArgument,
                         "'" + certPath + "' and '" + keyPath +
                             "' are not a PEM certificate and its key: " + gnutls_strerror(loaded));
    return TlsFiles{std::move(*cert), std::move(*key)};
}

} // namespace overlayd
