// CURVE key files (transport/curve_key.h, curve_keygen.h): what `crashlink keygen` writes reads
// back, and every malformed file is a CurveKeyFileError naming the file and the line.
#include "transport/curve_key.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>

#include "curve_test_support.h"
#include "transport/curve_errors.h"
#include "transport/curve_keygen.h"

namespace crashlink::transport::test {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

unsigned mode_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
  return st.st_mode & 0777u;
}

/// The error reading `path` as `kind`, or a failure if it reads.
CurveKeyFileError key_error(const std::string& path, bool secret = false) {
  try {
    (void)read_curve_key_file(path, secret ? "secret key" : "server public key", secret);
  } catch (const CurveKeyFileError& e) {
    return e;
  }
  ADD_FAILURE() << path << " was read as a key";
  return CurveKeyFileError("", 0, "", "");
}

TEST(CurveKey, KeygenPairReadsBackWithModes) {
  const KeyDir dir;
  const auto files = dir.pair("wiper");
  EXPECT_EQ(files.secret_file, dir.path("wiper.key"));
  EXPECT_EQ(files.public_file, dir.path("wiper.pub"));
  EXPECT_EQ(mode_of(files.secret_file), 0600u);
  EXPECT_EQ(mode_of(files.public_file), 0644u);
  const std::string secret = read_curve_key_file(files.secret_file, "secret key", true);
  const std::string pub = read_curve_key_file(files.public_file, "public key", false);
  EXPECT_EQ(pub, files.public_key);
  EXPECT_EQ(curve_public_key(secret), pub);
  EXPECT_NE(secret, pub);
  // The public file is also a valid authorized-keys file.
  EXPECT_EQ(read_authorized_keys(files.public_file), std::vector<std::string>{pub});
}

TEST(CurveKey, KeygenRefusesToOverwriteUnlessForced) {
  const KeyDir dir;
  const auto first = dir.pair("body");
  try {
    (void)dir.pair("body");
    ADD_FAILURE() << "a second keygen to the same prefix overwrote the keys";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), "body.key exists already")) << e.what();
    EXPECT_TRUE(has(e.what(), "--force")) << e.what();
  }
  EXPECT_EQ(read_curve_key_file(first.public_file, "public key", false), first.public_key);
  const auto second = write_curve_keypair(dir.path("body"), true);
  EXPECT_NE(second.public_key, first.public_key);
  EXPECT_EQ(read_curve_key_file(second.public_file, "public key", false), second.public_key);
  EXPECT_EQ(mode_of(second.secret_file), 0600u);
}

TEST(CurveKey, KeygenNeedsAFilePrefix) {
  const KeyDir dir;
  EXPECT_THROW((void)write_curve_keypair(dir.path("") + "/", false), InputError);
  EXPECT_THROW((void)write_curve_keypair(dir.path("no/such/dir/k"), false), InputError);
}

TEST(CurveKey, WrongLengthNamesFileLineAndLength) {
  const KeyDir dir;
  const auto pub = dir.pair("k").public_key;
  // The first 39 characters: a Z85 key never starts with '#' (84 * 85^4 > 2^32), so the line is
  // not a comment. (Dropping the first character instead made it one whenever the key's second
  // character was '#', one run in 85.)
  const std::string path = dir.write("short.pub", "# a comment\n" + pub.substr(0, 39) + "\n");
  const auto e = key_error(path);
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.line(), 2);
  EXPECT_TRUE(has(e.what(), path + ":2: server public key:")) << e.what();
  EXPECT_TRUE(has(e.what(), "39 characters, a Z85 key has 40")) << e.what();
  EXPECT_TRUE(has(e.what(), "crashlink keygen")) << e.what();
}

TEST(CurveKey, CharacterOutsideZ85) {
  const KeyDir dir;
  std::string key = dir.pair("k").public_key;
  key[7] = '"';
  const auto e = key_error(dir.write("quote.pub", key + "\n"));
  EXPECT_EQ(e.line(), 1);
  EXPECT_TRUE(has(e.what(), "character 8 (code 34) is not in the Z85 alphabet")) << e.what();
}

TEST(CurveKey, GroupAbove2To32) {
  const KeyDir dir;
  const std::string key = "$$$$$" + dir.pair("k").public_key.substr(5);
  EXPECT_FALSE(curve_key_problem(key).empty());
  const auto e = key_error(dir.write("big.pub", "\n\n" + key + "\n"));
  EXPECT_EQ(e.line(), 3);
  EXPECT_TRUE(has(e.what(), "above 2^32")) << e.what();
}

TEST(CurveKey, SecretKeyTextIsNeverInTheMessage) {
  const KeyDir dir;
  const std::string secret = read_curve_key_file(dir.pair("k").secret_file, "secret key", true);
  const std::string bad = secret.substr(0, 39) + "\"";
  const auto e = key_error(dir.write("bad.key", bad + "\n"), true);
  EXPECT_EQ(e.line(), 1);
  EXPECT_TRUE(has(e.what(), "not a Z85 key")) << e.what();
  EXPECT_FALSE(has(e.what(), secret.substr(0, 20))) << e.what();
}

TEST(CurveKey, OneKeyFileWithTwoKeys) {
  const KeyDir dir;
  const std::string a = dir.pair("a").public_key;
  const std::string b = dir.pair("b").public_key;
  const auto e = key_error(dir.write("two.pub", a + "\n# b:\n" + b + "\n"));
  EXPECT_EQ(e.line(), 3);
  EXPECT_TRUE(has(e.what(), "a second key (the first is on line 1)")) << e.what();
}

TEST(CurveKey, EmptyAndMissingFiles) {
  const KeyDir dir;
  const auto empty = key_error(dir.write("empty.pub", "# only a comment\n\n"));
  EXPECT_EQ(empty.line(), 2);
  EXPECT_TRUE(has(empty.what(), "no key in the file (2 lines)")) << empty.what();
  const auto missing = key_error(dir.path("absent.pub"));
  EXPECT_EQ(missing.line(), 0);
  EXPECT_TRUE(has(missing.what(), "cannot open the file (No such file or directory)"))
      << missing.what();
}

TEST(CurveKey, TextAfterAKeyMustBeAComment) {
  const KeyDir dir;
  const std::string key = dir.pair("k").public_key;
  const auto e = key_error(dir.write("tail.pub", key + " wiper-host\n"));
  EXPECT_EQ(e.line(), 1);
  EXPECT_TRUE(has(e.what(), "text after the key that is not a '#' comment ('wiper-host')"))
      << e.what();
  EXPECT_EQ(read_curve_key_file(dir.write("ok.pub", key + "   # wiper-host\r\n"), "k", false), key);
}

TEST(CurveKey, AuthorizedKeysCommentsBlanksDuplicates) {
  const KeyDir dir;
  const std::string a = dir.pair("a").public_key;
  const std::string b = dir.pair("b").public_key;
  // '#' is a Z85 character, but no key starts with it (84 * 85^4 > 2^32): a line starting with
  // '#' is a comment even when it looks like a key.
  const std::string hash_line = "#" + dir.pair("c").public_key.substr(1);
  EXPECT_FALSE(curve_key_problem(hash_line).empty());
  const std::string path =
      dir.write("authorized", "# daemons of the head-impact run\n\n  " + a + "  # wiper\r\n" + b +
                                  "\n" + a + "\n" + hash_line + "\n# end\n");
  EXPECT_EQ(read_authorized_keys(path), (std::vector<std::string>{a, b}));
  const auto e = [&] {
    try {
      (void)read_authorized_keys(dir.write("bad", a + "\n" + b.substr(0, 30) + "\n"));
    } catch (const CurveKeyFileError& x) {
      return std::string(x.what());
    }
    return std::string("read");
  }();
  EXPECT_TRUE(has(e, ":2: authorized keys: '" + b.substr(0, 30) +
                         "' is not a Z85 key: 30 "
                         "characters"))
      << e;
}

}  // namespace
}  // namespace crashlink::transport::test
