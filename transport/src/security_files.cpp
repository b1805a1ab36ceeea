#include "security_files.h"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>
#include <openssl/x509v3.h>

#include <algorithm>
#include <memory>
#include <regex>
#include <string>
#include <utility>
#include <vector>

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

// an S/MIME document signed by the CA: any change to its text breaks the signature; returns the
// signed text
std::string verify_signed_document(const File& document, const File& ca_file, X509* ca) {
  Bio bio = open(document);
  BIO* content = nullptr;
  Pkcs7 signature(SMIME_read_PKCS7(bio.get(), &content));
  Bio content_owner(content);
  if (!signature) throw failure(document, "is not an S/MIME signed document (" + openssl_error() + ")");
  Store store = store_of(ca);
  Bio text(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(signature.get(), nullptr, store.get(), content, text.get(), PKCS7_TEXT) != 1) {
    throw failure(document, std::string("signature does not verify against ") + ca_file.key + " " + ca_file.path +
                                " (changed after signing, or signed by another CA): " + openssl_error());
  }
  char* data = nullptr;
  const long size = BIO_get_mem_data(text.get(), &data);
  return size > 0 ? std::string(data, static_cast<size_t>(size)) : std::string();
}

using NameParts = std::vector<std::pair<std::string, std::string>>;

// a distinguished name's attributes as (short name, value), in any order
NameParts parts_of(const X509_NAME* name) {
  NameParts parts;
  for (int i = 0; i < X509_NAME_entry_count(name); ++i) {
    const X509_NAME_ENTRY* entry = X509_NAME_get_entry(name, i);
    const int nid = OBJ_obj2nid(X509_NAME_ENTRY_get_object(entry));
    const ASN1_STRING* value = X509_NAME_ENTRY_get_data(entry);
    parts.emplace_back(OBJ_nid2sn(nid), std::string(reinterpret_cast<const char*>(ASN1_STRING_get0_data(value)),
                                                   static_cast<size_t>(ASN1_STRING_length(value))));
  }
  std::sort(parts.begin(), parts.end());
  return parts;
}

// "CN=follower,O=teleop" (a permissions document's subject_name) as the same parts
NameParts parts_of(const std::string& text) {
  NameParts parts;
  static const std::regex part(R"(\s*([A-Za-z]+)\s*=\s*([^,]*[^,\s])\s*(,|$))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), part); it != std::sregex_iterator(); ++it) {
    parts.emplace_back((*it)[1], (*it)[2]);
  }
  std::sort(parts.begin(), parts.end());
  return parts;
}

// Fast DDS grants a participant the permissions whose subject_name is its certificate's subject;
// a document for another subject leaves it with none, and it says only "initialization error"
void verify_permissions_subject(const std::string& permissions_text, const File& permissions, X509* cert,
                                const File& cert_file) {
  const NameParts subject = parts_of(X509_get_subject_name(cert));
  static const std::regex subject_name("<subject_name>([^<]*)</subject_name>");
  std::string named;
  for (auto it = std::sregex_iterator(permissions_text.begin(), permissions_text.end(), subject_name);
       it != std::sregex_iterator(); ++it) {
    if (parts_of((*it)[1].str()) == subject) return;
    named += (named.empty() ? "" : ", ") + (*it)[1].str();
  }
  char* text = X509_NAME_oneline(X509_get_subject_name(cert), nullptr, 0);
  const std::string ours = text != nullptr ? text : "?";
  OPENSSL_free(text);
  throw failure(permissions, "grants nothing to the subject of " + std::string(cert_file.key) + " " + cert_file.path +
                                 " (" + ours + "); it names " + (named.empty() ? "no subject" : named));
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
  const std::string granted = verify_signed_document(permissions, permissions_ca, permissions_authority.get());
  verify_permissions_subject(granted, permissions, cert.get(), identity);
}

}  // namespace teleop::transport
