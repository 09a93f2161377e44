// Authentication (SPEC.md §2.1, protocol 1.7): the key file (its mode is what
// keeps the secret), the run's key folder, and a CURVE socket that answers the
// key holder and no stranger.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "dfc/common/errors.hpp"
#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/client.hpp"
#include "dfc/protocol/heartbeat_responder.hpp"
#include "dfc/protocol/key_file.hpp"
#include "dfc/protocol/run_key_file.hpp"

namespace dfc::protocol {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

/// A fresh folder for one test, removed after it.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name)
      : path_(fs::temp_directory_path() / ("dfc-authentication-test-" + std::to_string(::getpid()) + "-" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

mode_t permissions_of(const fs::path& path) {
  struct stat status {};
  EXPECT_EQ(::lstat(path.c_str(), &status), 0) << path;
  return status.st_mode & 07777;
}

std::string error_reading(const fs::path& path) {
  try {
    (void)read_key_file(path);
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(KeyFile, IsWrittenWithMode0600AndReadsBackTheSameKeys) {
  const ScratchFolder folder("round_trip");
  const auto keys = authentication::generate_key_pair();
  const mode_t umask_before = ::umask(0);  // the mode must not depend on the umask
  write_key_file(folder.path() / "server.key", keys);
  ::umask(umask_before);
  EXPECT_EQ(permissions_of(folder.path() / "server.key"), 0600u);
  const auto read = read_key_file(folder.path() / "server.key");
  EXPECT_EQ(read.public_key, keys.public_key);
  EXPECT_EQ(read.secret_key, keys.secret_key);
  EXPECT_EQ(keys.public_key.size(), 40u);
  EXPECT_NE(authentication::generate_key_pair().secret_key, keys.secret_key);
}

TEST(KeyFile, ThatOthersMayReadIsRefusedNamingTheFix) {
  const ScratchFolder folder("readable");
  const fs::path file = folder.path() / "server.key";
  write_key_file(file, authentication::generate_key_pair());
  ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
  const std::string error = error_reading(file);
  EXPECT_NE(error.find("mode 0640"), std::string::npos) << error;
  EXPECT_NE(error.find("chmod 600 " + file.string()), std::string::npos) << error;
}

// Root may read any user's file: a key file of another user's is still refused.
TEST(KeyFile, OfAnotherUserIsRefused) {
  if (::geteuid() != 0) GTEST_SKIP() << "only root can give a file to another user";
  const ScratchFolder folder("other_user");
  const fs::path file = folder.path() / "server.key";
  write_key_file(file, authentication::generate_key_pair());
  ASSERT_EQ(::chown(file.c_str(), 65534, 65534), 0);
  EXPECT_NE(error_reading(file).find("belongs to another user (uid 65534)"), std::string::npos) << error_reading(file);
}

TEST(KeyFile, WhoseKeysDoNotBelongTogetherIsRefused) {
  const ScratchFolder folder("mismatched");
  const fs::path file = folder.path() / "server.key";
  write_key_file(file, {authentication::generate_key_pair().public_key, authentication::generate_key_pair().secret_key});
  EXPECT_NE(error_reading(file).find("public_key is not the public key of secret_key"), std::string::npos) << error_reading(file);
}

TEST(KeyFile, ThatIsNoKeyFileIsRefusedNamingTheKeyAndTheFix) {
  const ScratchFolder folder("garbage");
  const fs::path file = folder.path() / "server.key";
  std::ofstream(file) << R"({"dfc_key_file": 1, "public_key": "short", "secret_key": "short"})";
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write);
  const std::string error = error_reading(file);
  EXPECT_NE(error.find("needs 'public_key', 40 characters of Z85"), std::string::npos) << error;
  EXPECT_NE(error.find("coupler keys FILE"), std::string::npos) << error;
  EXPECT_NE(error_reading(folder.path() / "missing.key").find("cannot open it"), std::string::npos);
}

TEST(RunKeyFile, LiesInAPrivateFolderAndIsRemovedWithTheRun) {
  const ScratchFolder folder("run");
  fs::path file;
  {
    const RunKeyFile run_keys(folder.path());
    file = run_keys.path();
    EXPECT_EQ(file.parent_path(), folder.path() / "keys");
    EXPECT_EQ(permissions_of(folder.path() / "keys"), 0700u);
    EXPECT_EQ(permissions_of(file), 0600u);
    EXPECT_EQ(read_key_file(file).public_key, run_keys.keys().public_key);
    EXPECT_EQ(run_keys.environment_entry(), "DFC_KEY_FILE=" + file.string());
  }
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(fs::exists(folder.path() / "keys"));
}

TEST(RunKeyFile, MakesAFolderLeftOpenByAnEarlierRunPrivateAgain) {
  const ScratchFolder folder("reused");
  fs::create_directories(folder.path() / "keys");
  ASSERT_EQ(::chmod((folder.path() / "keys").c_str(), 0755), 0);
  const RunKeyFile run_keys(folder.path());
  EXPECT_EQ(permissions_of(folder.path() / "keys"), 0700u);
}

Message ping() {
  Message request;
  request.type = std::string(type::ping);
  return request;
}

/// The heartbeat's ROUTER, secured as a server secures every socket it binds.
struct SecuredResponder {
  zmq::context_t context{1};
  Liveness liveness;
  authentication::CurveKeyPair keys = authentication::generate_key_pair();
  HeartbeatResponder responder{context, "tcp://127.0.0.1:*", liveness, "1.7", keys};
};

TEST(Authentication, ACurveSocketAnswersTheKeyHolderAndNoStranger) {
  SecuredResponder server;
  const std::string endpoint = server.responder.endpoint();
  Connection without_key(server.context, endpoint, "a stranger without a key");
  EXPECT_THROW((void)without_key.request_raw(ping(), 500ms), TimeoutError);
  Connection other_key(server.context, endpoint, "a stranger with another key", Limits{}, authentication::generate_key_pair().public_key);
  EXPECT_THROW((void)other_key.request_raw(ping(), 500ms), TimeoutError);

  Connection key_holder(server.context, endpoint, "the key holder", Limits{}, server.keys.public_key);
  EXPECT_EQ(key_holder.request_raw(ping(), 2s).type, "pong");
}

// A client without the key whose handshake has already failed when it sends:
// libzmq ends the session on the protocol error and the DEALER is left with no
// pipe, where a blocking send waited for ever (seen as a conformance check hung
// under the sanitizers, which made the failure come first now and then). It
// is a TimeoutError at once, naming the key.
TEST(Authentication, AClientRefusedBeforeItSendsGetsATimeoutNotAHang) {
  SecuredResponder server;
  Connection without_key(server.context, server.responder.endpoint(), "a stranger without a key");
  // The handshake of a NULL client with a CURVE server fails within a few
  // milliseconds on loopback; a second leaves no doubt it came first.
  std::this_thread::sleep_for(1s);
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)without_key.request_raw(ping(), 500ms);
    ADD_FAILURE() << "a client without the key was answered";
  } catch (const TimeoutError& e) {
    // Either way round it is a timeout: refused before the send (the key named)
    // or after it (unanswered).
    const std::string what = e.what();
    EXPECT_TRUE(what.find("key") != std::string::npos || what.find("did not answer") != std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
}

}  // namespace
}  // namespace dfc::protocol
