// verify_security_files against a PKI made by scripts/make_pki.sh (a process: run at test time,
// nothing secret committed), and against the files broken one at a time.
#include "security_files.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "process_helpers.h"

namespace teleop::transport {
namespace {
namespace fs = std::filesystem;

class SecurityFiles : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(test::make_temp_dir());
    const auto r =
        test::run_process({"/bin/bash", test::source("scripts/make_pki.sh"), *dir_ + "/pki"}, std::chrono::seconds(60));
    ASSERT_EQ(r.exit_status, 0) << r.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  static SecurityConfig config_of(const std::string& node) {
    const std::string pki = *dir_ + "/pki";
    return {pki + "/identity_ca.pem",      pki + "/" + node + "/identity.pem",
            pki + "/" + node + "/key.pem", pki + "/permissions_ca.pem",
            pki + "/governance.p7s",       pki + "/" + node + "/permissions.p7s"};
  }

  static std::string error_of(const SecurityConfig& c) {
    try {
      verify_security_files(c);
    } catch (const SecurityFileError& e) {
      return e.what();
    }
    return "no error";
  }

  static std::string* dir_;
};

std::string* SecurityFiles::dir_ = nullptr;

TEST_F(SecurityFiles, AcceptsEveryNodeOfTheMadePki) {
  for (const char* node : {"leader", "follower", "twin"})
    EXPECT_NO_THROW(verify_security_files(config_of(node))) << node;
}

TEST_F(SecurityFiles, NamesAPrivateKeyOfAnotherNode) {
  SecurityConfig c = config_of("leader");
  c.private_key = config_of("follower").private_key;
  EXPECT_EQ(error_of(c), "security.private_key " + c.private_key + ": does not belong to identity_certificate " +
                             c.identity_certificate);
}

TEST_F(SecurityFiles, NamesATamperedGovernance) {
  SecurityConfig c = config_of("leader");
  const std::string copy = *dir_ + "/governance.p7s";
  std::string text = test::read_file(c.governance);
  const std::string rule = "<data_protection_kind>ENCRYPT</data_protection_kind>";
  ASSERT_NE(text.find(rule), std::string::npos);
  text.replace(text.find(rule), rule.size(), "<data_protection_kind>NONE</data_protection_kind>");
  test::write_file(copy, text);
  c.governance = copy;
  EXPECT_EQ(
      error_of(c).rfind(
          "security.governance " + copy + ": signature does not verify against permissions_ca " + c.permissions_ca, 0),
      0u)
      << error_of(c);
}

TEST_F(SecurityFiles, NamesACertificateWhereACaShouldBe) {
  SecurityConfig c = config_of("leader");
  c.permissions_ca = c.identity_ca;  // the wrong CA signed nothing here
  EXPECT_EQ(error_of(c).rfind("security.governance " + c.governance + ": signature does not verify", 0), 0u)
      << error_of(c);
}

TEST_F(SecurityFiles, NamesPermissionsThatGrantNothingToTheCertificatesSubject) {
  // the follower's permissions beside the leader's certificate: both genuine, signed by the CA
  SecurityConfig c = config_of("leader");
  c.permissions = config_of("follower").permissions;
  const std::string error = error_of(c);
  EXPECT_EQ(error.rfind("security.permissions " + c.permissions + ": grants nothing to the subject of identity_certificate " +
                            c.identity_certificate,
                        0),
            0u)
      << error;
  EXPECT_NE(error.find("it names CN=follower,O=teleop"), std::string::npos) << error;
}

TEST_F(SecurityFiles, NamesAFileThatIsNotPem) {
  SecurityConfig c = config_of("leader");
  c.identity_certificate = c.permissions;  // S/MIME, not a certificate
  EXPECT_EQ(error_of(c).rfind("security.identity_certificate " + c.permissions + ": is not a PEM certificate", 0), 0u)
      << error_of(c);
}

}  // namespace
}  // namespace teleop::transport
