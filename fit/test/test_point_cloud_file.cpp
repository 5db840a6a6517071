// Point cloud files: what each format reads, and every bad file refused with its name (and line).

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "point_cloud_file.h"

namespace fse_fit {
namespace {

class CloudFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("fse_fit_files_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& bytes) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  // The message of readPointCloud's CloudFileError, or "" if it read the file.
  static std::string refusal(const std::string& path) {
    try {
      readPointCloud(path);
    } catch (const CloudFileError& e) {
      return e.what();
    }
    return "";
  }
  std::filesystem::path dir_;
};

template <typename T>
std::string bytesOf(T value, bool big_endian) {
  std::string b(sizeof(T), '\0');
  std::memcpy(b.data(), &value, sizeof(T));
  if (big_endian) std::reverse(b.begin(), b.end());
  return b;
}

TEST_F(CloudFiles, XyzSkipsCommentsBlankLinesAndExtraColumns) {
  const auto points =
      readPointCloud(write("c.xyz", "# a comment\n1 2 3\n\n-4.5e-1 5 6 0 0 1\r\n7 8 9\n"));
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[1], Eigen::Vector3d(-0.45, 5, 6));
  EXPECT_EQ(points[2], Eigen::Vector3d(7, 8, 9));
}

TEST_F(CloudFiles, AsciiPlyReadsTheVertexElementWhateverItsPropertyOrder) {
  const auto points =
      readPointCloud(write("c.PLY",
                           "ply\nformat ascii 1.0\ncomment made by hand\n"
                           "element vertex 2\nproperty float nx\nproperty float z\n"
                           "property double x\nproperty uchar red\nproperty float y\n"
                           "element face 1\nproperty list uchar int vertex_indices\n"
                           "end_header\n0 3 1 255 2\n0 6 4 0 5\n3 0 1 1\n"));
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(points[1], Eigen::Vector3d(4, 5, 6));
}

TEST_F(CloudFiles, BinaryPlyInBothByteOrders) {
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    std::string body;
    for (int i = 0; i < 3; ++i) {
      body += bytesOf<double>(0.5 + i, big) + bytesOf<float>(-1.25f * i, big) +
              bytesOf<std::int16_t>(static_cast<std::int16_t>(7 * i), big) +
              bytesOf<std::uint8_t>(9, big);
    }
    const std::string header = std::string("ply\nformat ") +
                               (big ? "binary_big_endian" : "binary_little_endian") +
                               " 1.0\nelement vertex 3\nproperty double x\nproperty float y\n"
                               "property short z\nproperty uchar alpha\nend_header\n";
    const auto points = readPointCloud(write(big ? "b.ply" : "l.ply", header + body));
    ASSERT_EQ(points.size(), 3u);
    EXPECT_EQ(points[2], Eigen::Vector3d(2.5, -2.5, 14));
  }
}

TEST_F(CloudFiles, BadFilesAreRefusedWithTheirNameAndLine) {
  struct Case {
    const char* name;
    const char* file;
    const char* bytes;
    const char* expected;  // in the message, after the file's name
  };
  const Case cases[] = {
      {"not a number", "a.xyz", "1 2 3\n1 x 3\n", ":2: expected a number, got 'x'"},
      {"two numbers", "b.xyz", "1 2\n", ":1: expected three numbers x y z, got '1 2'"},
      {"not finite", "c.xyz", "1 2 3\n4 inf 6\n", ":2: point 1 is not finite"},
      {"no point", "d.xyz", "# nothing\n\n", ": no point"},
      {"unknown extension", "e.pcd", "1 2 3\n", "unknown point cloud format 'pcd'"},
      {"not ply", "f.ply", "plx\n", ":1: not a PLY file"},
      {"no end_header", "g.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", "no 'end_header'"},
      {"unknown format", "h.ply", "ply\nformat binary_middle 1.0\nend_header\n",
       "unknown PLY format 'binary_middle'"},
      {"no vertex", "i.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n",
       "no 'vertex' element"},
      {"no z", "j.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
       "end_header\n1 2\n",
       "lacks one of the properties x, y, z"},
      {"unknown type", "k.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
       ":4: unknown PLY type 'quad'"},
      {"short ascii", "l.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nend_header\n1 2 3\n",
       "the file ends after 1 of 3 vertices"},
      {"wrong value count", "m.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
       "property float z\nend_header\n1 2 3 4\n",
       ":8: expected 3 values, got 4"},
      {"short binary", "n.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
       "property float y\nproperty float z\nend_header\n123456789012",
       "the file ends after 1 of 2 vertices"},
      {"vertex list", "o.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
       "property float z\nproperty list uchar int n\nend_header\n1 2 3 0\n",
       "a list property in the vertex element"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = write(c.file, c.bytes);
    const std::string message = refusal(path);
    EXPECT_EQ(message.rfind(path, 0), 0u) << message;  // starts with the file's name
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
  const std::string missing = (dir_ / "missing.xyz").string();
  EXPECT_NE(refusal(missing).find(missing + ": cannot open"), std::string::npos);
}

}  // namespace
}  // namespace fse_fit
