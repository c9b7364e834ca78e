// SPDX-License-Identifier: Apache-2.0
// TlsCertificate: PEM to GnuTLS's certificate list and private key, and the retrieve callback that serves them.
#include "http/tls_certificate.h"

#include <gnutls/abstract.h>
#include <gnutls/gnutls.h>
#include <vector>

namespace overlayd {

namespace {

constexpr unsigned kMaxChain = 16; // certificates in tls_cert (the server's and its intermediates)

struct Served {
    std::unique_ptr<TlsCertificate> current, previous;
};

Served &served()
{
    static Served instance; // see serve(): GnuTLS's callback has no user pointer
    return instance;
}

gnutls_datum_t datum(const std::string &text)
{
    return {reinterpret_cast<unsigned char *>(const_cast<char *>(text.data())), unsigned(text.size())};
}

} // namespace

struct TlsCertificate::Parts {
    std::vector<gnutls_pcert_st> chain;
    gnutls_privkey_t key = nullptr;
    ~Parts()
    {
        for (gnutls_pcert_st &cert : chain)
            gnutls_pcert_deinit(&cert);
        if (key)
            gnutls_privkey_deinit(key);
    }
};

Result<std::unique_ptr<TlsCertificate>> TlsCertificate::create(const TlsFiles &files)
{
    std::unique_ptr<TlsCertificate> out(new TlsCertificate);
    out->parts_ = std::make_unique<Parts>();
    Parts &parts = *out->parts_;
    parts.chain.resize(kMaxChain);
    unsigned count = kMaxChain;
    const gnutls_datum_t cert = datum(files.certPem), key = datum(files.keyPem);
    if (int e = gnutls_pcert_list_import_x509_raw(parts.chain.data(), &count, &cert, GNUTLS_X509_FMT_PEM, 0); e < 0) {
        parts.chain.clear();
        return makeError(ErrorCode::InvalidArgument, std::string("http.tls_cert: ") + gnutls_strerror(e));
    }
    parts.chain.resize(count);
    if (gnutls_privkey_init(&parts.key) < 0)
        return makeError(ErrorCode::Io, "GnuTLS could not allocate a private key");
    if (int e = gnutls_privkey_import_x509_raw(parts.key, &key, GNUTLS_X509_FMT_PEM, nullptr, 0); e < 0)
        return makeError(ErrorCode::InvalidArgument, std::string("http.tls_key: ") + gnutls_strerror(e));
    return out;
}

TlsCertificate::~TlsCertificate() = default;

void TlsCertificate::serve(std::unique_ptr<TlsCertificate> certificate)
{
    Served &s = served();
    s.previous = std::move(s.current);
    s.current = std::move(certificate);
}

namespace {

int retrieve(gnutls_session_t, const gnutls_datum_t *, int, const gnutls_pk_algorithm_t *, int, gnutls_pcert_st **chain,
             unsigned *length, gnutls_privkey_t *key)
{
    const TlsCertificate *current = served().current.get();
    if (!current)
        return -1; // no certificate in service: the handshake fails
    // Borrowed: GnuTLS frees neither (the certificate lives until two changes later, see serve()).
    TlsCertificate::Parts &parts = current->parts();
    *chain = parts.chain.data();
    *length = unsigned(parts.chain.size());
    *key = parts.key;
    return 0;
}

} // namespace

void *TlsCertificate::callback()
{
    gnutls_certificate_retrieve_function2 *function = &retrieve;
    return reinterpret_cast<void *>(function);
}

} // namespace overlayd
