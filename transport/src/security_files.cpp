#include "security_files.h"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>
#include <openssl/x509v3.h>

#include <memory>
#include <string>

namespace teleop::transport {
namespace {

template <auto Free>
struct Deleter {
  template <typename T>
  void operator()(T* p) const {
    Free(p);
  }
};
using Bio = std::unique_ptr<BIO, Deleter<BIO_free_all>>;
using Certificate = std::unique_ptr<X509, Deleter<X509_free>>;
using PrivateKey = std::unique_ptr<EVP_PKEY, Deleter<EVP_PKEY_free>>;
using Store = std::unique_ptr<X509_STORE, Deleter<X509_STORE_free>>;
using StoreContext = std::unique_ptr<X509_STORE_CTX, Deleter<X509_STORE_CTX_free>>;
using Pkcs7 = std::unique_ptr<PKCS7, Deleter<PKCS7_free>>;

// one file named by its config key and path
struct File {
  const char* key;
  const std::string& path;
};

SecurityFileError failure(const File& file, const std::string& problem) {
  return SecurityFileError("security." + std::string(file.key) + " " + file.path + ": " + problem);
}

// the last queued OpenSSL error as text; clears the queue
std::string openssl_error() {
  const unsigned long code = ERR_get_error();
  ERR_clear_error();
  if (code == 0) return "no detail from OpenSSL";
  char text[256];
  ERR_error_string_n(code, text, sizeof text);
  return text;
}

Bio open(const File& file) {
  Bio bio(BIO_new_file(file.path.c_str(), "r"));
  if (!bio) throw failure(file, "cannot be read (" + openssl_error() + ")");
  return bio;
}

Certificate load_certificate(const File& file) {
  Bio bio = open(file);
  Certificate cert(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
  if (!cert) throw failure(file, "is not a PEM certificate (" + openssl_error() + ")");
  return cert;
}

// a trust store holding only `ca`; any purpose, since the CAs here sign documents as well
Store store_of(X509* ca) {
  Store store(X509_STORE_new());
  if (!store || X509_STORE_add_cert(store.get(), ca) != 1 ||
      X509_STORE_set_purpose(store.get(), X509_PURPOSE_ANY) != 1) {
    throw SecurityFileError("security: cannot build a certificate store: " + openssl_error());
  }
  return store;
}

void verify_certificate(const File& cert_file, X509* cert, const File& ca_file, X509* ca) {
  Store store = store_of(ca);
  StoreContext context(X509_STORE_CTX_new());
  if (!context || X509_STORE_CTX_init(context.get(), store.get(), cert, nullptr) != 1) {
    throw SecurityFileError("security: cannot set up certificate verification: " + openssl_error());
  }
  if (X509_verify_cert(context.get()) != 1) {
    const int error = X509_STORE_CTX_get_error(context.get());
    throw failure(cert_file, std::string(X509_verify_cert_error_string(error)) + " (verified against " + ca_file.key +
                                 " " + ca_file.path + ")");
  }
}

void verify_private_key(const File& key_file, X509* cert, const File& cert_file) {
  Bio bio = open(key_file);
  PrivateKey key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
  if (!key) throw failure(key_file, "is not an unencrypted PEM private key (" + openssl_error() + ")");
  if (X509_check_private_key(cert, key.get()) != 1) {
    ERR_clear_error();
    throw failure(key_file, std::string("does not belong to ") + cert_file.key + " " + cert_file.path);
  }
}

// an S/MIME document signed by the CA: any change to its text breaks the signature
void verify_signed_document(const File& document, const File& ca_file, X509* ca) {
  Bio bio = open(document);
  BIO* content = nullptr;
  Pkcs7 signature(SMIME_read_PKCS7(bio.get(), &content));
  Bio content_owner(content);
  if (!signature) throw failure(document, "is not an S/MIME signed document (" + openssl_error() + ")");
  Store store = store_of(ca);
  if (PKCS7_verify(signature.get(), nullptr, store.get(), content, nullptr, PKCS7_TEXT) != 1) {
    throw failure(document, std::string("signature does not verify against ") + ca_file.key + " " + ca_file.path +
                                " (changed after signing, or signed by another CA): " + openssl_error());
  }
}

}  // namespace

void verify_security_files(const SecurityConfig& s) {
  const File identity_ca{"identity_ca", s.identity_ca};
  const File identity{"identity_certificate", s.identity_certificate};
  const File private_key{"private_key", s.private_key};
  const File permissions_ca{"permissions_ca", s.permissions_ca};
  const File governance{"governance", s.governance};
  const File permissions{"permissions", s.permissions};

  const Certificate ca = load_certificate(identity_ca);
  const Certificate cert = load_certificate(identity);
  verify_certificate(identity, cert.get(), identity_ca, ca.get());
  verify_private_key(private_key, cert.get(), identity);

  const Certificate permissions_authority = load_certificate(permissions_ca);
  verify_signed_document(governance, permissions_ca, permissions_authority.get());
  verify_signed_document(permissions, permissions_ca, permissions_authority.get());
}

}  // namespace teleop::transport
