// PLY in its three encodings, with extra properties and polygons, gives the same triangles.
#include <bit>
#include <cstring>

#include <gtest/gtest.h>

#include "runtime/scene/scene.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using test::TempDir;

// Four vertices (double x/y/z between float and int extras), one quad and one triangle, each face
// with an extra uchar before its list and an int after it, plus an unrelated element at the end.
const char* kHeaderBody =
    "comment made by the Cohort scene tests\n"
    "element vertex 4\n"
    "property float nx\n"
    "property double x\n"
    "property double y\n"
    "property double z\n"
    "property int flags\n"
    "element face 2\n"
    "property uchar intensity\n"
    "property list uchar uint vertex_indices\n"
    "property int flags\n"
    "element edge 1\n"
    "property list int short pair\n"
    "end_header\n";

const double kVertices[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0.25}};

std::string ascii_ply() {
  return std::string("ply\nformat ascii 1.0\n") + kHeaderBody +
         "0.5 0 0 0 7\n0.5 1 0 0 7\n0.5 1 1 0.5 7\n0.5 0 1 0.25 7\n"
         "9 4 0 1 2 3 -1\n"
         "9 3 0 2 3 -1\n"
         "2 0 1\n";
}

class BinaryWriter {
 public:
  explicit BinaryWriter(bool big) : big_(big) {}
  template <typename T>
  BinaryWriter& put(T value) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (big_ != (std::endian::native == std::endian::big))
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    bytes.append(b, sizeof(T));
    return *this;
  }
  std::string bytes;

 private:
  bool big_;
};

std::string binary_ply(bool big) {
  BinaryWriter w(big);
  for (const auto& v : kVertices) w.put(0.5f).put(v[0]).put(v[1]).put(v[2]).put(std::int32_t{7});
  w.put(std::uint8_t{9}).put(std::uint8_t{4});
  for (std::uint32_t i : {0u, 1u, 2u, 3u}) w.put(i);
  w.put(std::int32_t{-1});
  w.put(std::uint8_t{9}).put(std::uint8_t{3});
  for (std::uint32_t i : {0u, 2u, 3u}) w.put(i);
  w.put(std::int32_t{-1});
  w.put(std::int32_t{2}).put(std::int16_t{0}).put(std::int16_t{1});
  const char* format = big ? "binary_big_endian" : "binary_little_endian";
  return std::string("ply\nformat ") + format + " 1.0\n" + kHeaderBody + w.bytes;
}

TEST(Ply, AsciiLittleAndBigEndianGiveTheSameTriangles) {
  TempDir dir;
  test::write_file(dir / "a.ply", ascii_ply());
  test::write_file(dir / "le.ply", binary_ply(false));
  test::write_file(dir / "be.ply", binary_ply(true));
  const Scene a = load_scene(dir / "a.ply");
  const Scene le = load_scene(dir / "le.ply");
  const Scene be = load_scene(dir / "be.ply");
  ASSERT_EQ(a.triangle_count(), 3u);  // the quad fans into two
  const std::vector<glm::vec3> expected = {{0, 0, 0},     {1, 0, 0}, {1, 1, 0.5f}, {0, 0, 0},    {1, 1, 0.5f},
                                           {0, 1, 0.25f}, {0, 0, 0}, {1, 1, 0.5f}, {0, 1, 0.25f}};
  EXPECT_EQ(a.positions, expected);
  EXPECT_EQ(le.positions, expected);
  EXPECT_EQ(be.positions, expected);
  ASSERT_EQ(a.materials.size(), 1u);
  EXPECT_EQ(a.materials[0].name, "default");
  EXPECT_TRUE(a.uvs.empty());
}

TEST(Ply, CompressedPlyLoads) {
  TempDir dir;
  test::write_gzip(dir / "be.ply.gz", binary_ply(true));
  EXPECT_EQ(load_scene(dir / "be.ply.gz").triangle_count(), 3u);
}

TEST(Ply, HugeFaceCountInATinyFileIsRejectedBeforeAllocating) {
  TempDir dir;
  test::write_file(dir / "huge.ply",
                   "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   "element face 1099511627776\nproperty list uchar int vertex_indices\n"
                   "end_header\n" +
                       std::string(36 + 13, '\0'));
  test::expect_input_error(dir / "huge.ply", "1099511627776");
}

TEST(Ply, HugeListLengthIsRejected) {
  TempDir dir;
  BinaryWriter w(false);
  for (int i = 0; i < 9; ++i) w.put(0.f);
  w.put(std::uint32_t{4000000000u}).put(std::int32_t{0});
  test::write_file(dir / "list.ply",
                   "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uint int vertex_indices\n"
                   "end_header\n" +
                       w.bytes);
  test::expect_input_error(dir / "list.ply", "list length");
}

TEST(Ply, OutOfRangeIndexIsRejected) {
  TempDir dir;
  test::write_file(dir / "range.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                   "property float y\nproperty float z\nelement face 1\n"
                   "property list uchar int vertex_indices\nend_header\n"
                   "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  test::expect_input_error(dir / "range.ply", "vertex 3");
}

TEST(Ply, NegativeIndexIsRejected) {
  TempDir dir;
  test::write_file(dir / "negative.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                   "property float y\nproperty float z\nelement face 1\n"
                   "property list uchar int vertex_indices\nend_header\n"
                   "0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n");
  test::expect_input_error(dir / "negative.ply", "invalid vertex index");
}

TEST(Ply, TruncatedBinaryAndBadHeadersAreRejected) {
  TempDir dir;
  std::string truncated = binary_ply(false);
  truncated.resize(truncated.size() - 20);
  test::write_file(dir / "truncated.ply", truncated);
  test::expect_input_error(dir / "truncated.ply");
  test::write_file(dir / "nomagic.ply", "plx\nformat ascii 1.0\nend_header\n");
  test::expect_input_error(dir / "nomagic.ply", "magic");
  test::write_file(dir / "noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n");
  test::expect_input_error(dir / "noend.ply", "end_header");
  test::write_file(dir / "badtype.ply",
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n");
  test::expect_input_error(dir / "badtype.ply", "quad");
  test::write_file(dir / "headeronly.ply",
                   "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                   "property float x\nproperty float y\nproperty float z\nend_header");
  test::expect_input_error(dir / "headeronly.ply", "only 0 bytes");
  test::write_file(dir / "badnumber.ply",
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                   "property float y\nproperty float z\nend_header\n1 2 zz\n");
  test::expect_input_error(dir / "badnumber.ply", "zz");
}

TEST(Ply, NoFacesMeansNoTriangles) {
  TempDir dir;
  test::write_file(dir / "points.ply",
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                   "property float y\nproperty float z\nend_header\n1 2 3\n");
  test::expect_input_error(dir / "points.ply", "no triangles");
}

}  // namespace
}  // namespace cohort
