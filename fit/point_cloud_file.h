#ifndef FSE_FIT_POINT_CLOUD_FILE_H
#define FSE_FIT_POINT_CLOUD_FILE_H

// Point clouds from files, as perception tools exchange them (Open3D, PCL, CloudCompare):
//  - XYZ: text, one point per line, its first three numbers x y z (further columns such as
//    normals or colours are ignored); blank lines and lines starting with '#' are skipped.
//  - PLY: the "vertex" element's x, y, z properties (any PLY scalar type), in the ascii,
//    binary_little_endian or binary_big_endian format; other elements and properties are skipped.
// The format is told by the file's extension (.xyz, .txt, .ply, any case).
// docs/fitting.md → "Point cloud files".

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace fse_fit {

/// A file that cannot be read as a point cloud. The message starts with the file's name and, for
/// text, the line: "cloud.xyz:12: expected three numbers x y z, got 'a b'".
class CloudFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The points of an XYZ or PLY file. @throws CloudFileError if the file cannot be opened, is not
/// of its format, holds a non-finite coordinate or no point.
std::vector<Eigen::Vector3d> readPointCloud(const std::string& path);

}  // namespace fse_fit

#endif  // FSE_FIT_POINT_CLOUD_FILE_H
