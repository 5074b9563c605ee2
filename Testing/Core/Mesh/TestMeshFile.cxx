// The OFF/OBJ reader: every shared mesh with the README's counts, each feature real files use
// (in memory, with exact points and triangles), and hostile inputs (bad numbers and indices,
// truncation at every byte, binary junk, absurd counts) that must give a message naming the
// line, never a crash, a hang or a huge allocation.
#include "Mesh/MeshFile.h"

#include "MeshFiles.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>

using namespace otparam;

namespace
{

std::string readOffText(const std::string& text, MeshFileData& out)
{
  std::istringstream in(text);
  return readOFF(in, out);
}

std::string readObjText(const std::string& text, MeshFileData& out)
{
  std::istringstream in(text);
  return readOBJ(in, out);
}

void expectPoints(const MeshFileData& data, const std::vector<Vec3>& expected)
{
  ASSERT_EQ(data.points.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i)
  {
    EXPECT_EQ(data.points[i].x, expected[i].x) << "point " << i;
    EXPECT_EQ(data.points[i].y, expected[i].y) << "point " << i;
    EXPECT_EQ(data.points[i].z, expected[i].z) << "point " << i;
  }
}

void expectTriangles(const MeshFileData& data, const std::vector<Triangle>& expected)
{
  EXPECT_EQ(data.triangles, expected);
}

// What every answer must be: success with valid ids, or a message and an empty result.
void expectSane(const std::string& error, const MeshFileData& data)
{
  if (!error.empty())
  {
    EXPECT_TRUE(
      error.rfind("line ", 0) == 0 || error.find("(binary data at line ") != std::string::npos)
      << error;
    EXPECT_TRUE(data.points.empty() && data.triangles.empty() && data.format.empty());
    return;
  }
  EXPECT_FALSE(data.points.empty());
  EXPECT_FALSE(data.triangles.empty());
  for (const Triangle& t : data.triangles)
  {
    for (int v : t)
    {
      ASSERT_GE(v, 0);
      ASSERT_LT(v, static_cast<int>(data.points.size()));
    }
  }
  EXPECT_TRUE(
    data.textureCoordinates.empty() || data.textureCoordinates.size() == data.points.size());
}

// An error that contains `part` (the line number and what is wrong), result cleared.
void expectError(const std::string& error, const MeshFileData& data, const std::string& part)
{
  EXPECT_NE(error.find(part), std::string::npos)
    << "message: '" << error << "', expected '" << part << "' in it";
  EXPECT_TRUE(data.points.empty() && data.triangles.empty() && data.format.empty());
}

const std::vector<Vec3> unitSquare = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };

const char* const smallOff = "OFF\n"
                             "# a square and a triangle\n"
                             "5 2 0\n"
                             "0 0 0\n"
                             "1 0 0\n"
                             "1 1 0\n"
                             "0 1 0\n"
                             "0.5 2 0\n"
                             "4 0 1 2 3\n"
                             "3 3 2 4\n";

const char* const smallObj = "# a square and a triangle\n"
                             "mtllib m.mtl\n"
                             "v 0 0 0\n"
                             "v 1 0 0\n"
                             "v 1 1 0\n"
                             "v 0 1 0\n"
                             "v 0.5 2 0\n"
                             "vt 0 0\n"
                             "vt 1 0\n"
                             "vt 1 1\n"
                             "vt 0 1\n"
                             "vt 0.5 1\n"
                             "f 1/1 2/2 3/3 4/4\n"
                             "f -2/-2 -3/-3 -1/-1\n";

} // namespace

// ---- Shared meshes

namespace
{
struct SharedMesh
{
  const char* name;
  size_t vertices;
  size_t triangles;
};
// ../shared/data/meshes/README.md (bunny: every vertex of the file, referenced or not).
const SharedMesh sharedMeshes[] = {
  { "hand_stein_810.obj", 810, 1602 },
  { "hemisphere_2k.obj", 2051, 4000 },
  { "face_dense_gpp_5k.obj", 5101, 10000 },
  { "face_choi_bff_17k.obj", 17157, 34144 },
  { "chinese_lion_17k.off", 17334, 34421 },
  { "ogre_face_20k.obj", 19985, 39856 },
  { "face_maxplanck_partial_32k.obj", 31894, 63347 },
  { "brain_cortex_cut_48k.off", 48463, 96811 },
  { "hand_choi_53k.off", 53054, 105860 },
  { "bust_aphrodite_56k.obj", 55598, 110788 },
  { "brain_choi_closed_48k.off", 48487, 96970 },
  { "spot_closed_3k.obj", 2930, 5856 },
  { "bunny_holes_35k.obj", 35947, 69451 },
};
} // namespace

TEST(MeshFile, SharedMeshesHaveTheReadmeCounts)
{
  for (const SharedMesh& mesh : sharedMeshes)
  {
    MeshFileData data;
    const auto start = std::chrono::steady_clock::now();
    const std::string error = readMeshFile(otparam::testing::sharedMesh(mesh.name), data);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(error, "") << mesh.name;
    EXPECT_EQ(data.points.size(), mesh.vertices) << mesh.name;
    EXPECT_EQ(data.triangles.size(), mesh.triangles) << mesh.name;
    EXPECT_EQ(data.polygons, 0) << mesh.name;
    EXPECT_TRUE(data.textureCoordinates.empty()) << mesh.name;
    const std::string name = mesh.name;
    EXPECT_EQ(data.format, name.substr(name.size() - 3) == "off" ? "OFF" : "OBJ");
    std::cout << mesh.name << ": " << data.points.size() << " points, " << data.triangles.size()
              << " triangles in " << seconds << " s\n";
  }
}

// A mesh added to the shared folder must be added to the table above.
TEST(MeshFile, EverySharedMeshIsInTheTable)
{
  for (const auto& entry : std::filesystem::directory_iterator(OTPARAM_SHARED_MESH_DIR))
  {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".off" && entry.path().extension() != ".obj")
    {
      continue;
    }
    bool listed = false;
    for (const SharedMesh& mesh : sharedMeshes)
    {
      listed = listed || name == mesh.name;
    }
    EXPECT_TRUE(listed) << name;
  }
}

// `f 1/1 15/15 16/16` without any vt line (VTK 9.2's OBJ reader crashes on it).
TEST(MeshFile, TextureIndicesWithoutTextureCoordinates)
{
  MeshFileData data;
  ASSERT_EQ(readMeshFile(otparam::testing::sharedMesh("face_dense_gpp_5k.obj"), data), "");
  EXPECT_EQ(data.points.size(), 5101u);
  EXPECT_EQ(data.triangles.size(), 10000u);
  EXPECT_TRUE(data.textureCoordinates.empty());
  EXPECT_EQ(data.texturedCornersIgnored, 0); // no vt line: nothing lost, nothing to warn about
}

// ---- OFF features

TEST(MeshFile, OffPolygonsCommentsBlankLines)
{
  MeshFileData data;
  ASSERT_EQ(readOffText(smallOff, data), "");
  expectPoints(data, { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0.5, 2, 0 } });
  expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 }, { 3, 2, 4 } });
  EXPECT_EQ(data.polygons, 1);
  EXPECT_EQ(data.format, "OFF");
}

TEST(MeshFile, OffCountsOnTheHeaderLineCrlfTrailingComments)
{
  MeshFileData data;
  const std::string text = "\xEF\xBB\xBFOFF 4 2 0 # counts here\r\n"
                           "\r\n"
                           "  # whole-line comment\r\n"
                           "0 0 0 # a corner\r\n"
                           "1 0 0\r\n"
                           "\t1 1 0\r\n"
                           "0 1 0\r\n"
                           "3 0 1 2 # first\r\n"
                           "3 0 2 3\r\n";
  ASSERT_EQ(readOffText(text, data), "");
  expectPoints(data, unitSquare);
  expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 } });
  EXPECT_EQ(data.polygons, 0);
}

TEST(MeshFile, OffVariantsIgnoreExtraValues)
{
  const std::string body = "4 2 0\n"
                           "0 0 0 %\n"
                           "1 0 0 %\n"
                           "1 1 0 %\n"
                           "0 1 0 %\n"
                           "3 0 1 2 255 0 0\n"
                           "3 0 2 3 0.1 0.2 0.3 1.0\n";
  const std::map<std::string, std::string> extras = { { "OFF", "" }, { "COFF", "0.5 0.5 0.5 1" },
    { "NOFF", "0 0 1" }, { "CNOFF", "0 0 1 255 255 255 255" }, { "STOFF", "0.25 0.75" },
    { "STCNOFF", "0.1 0.2 0 0 1 9 9 9 9" } };
  for (const auto& [keyword, extra] : extras)
  {
    std::string text = keyword + "\n" + body;
    for (size_t at = text.find('%'); at != std::string::npos; at = text.find('%'))
    {
      text.replace(at, 1, extra);
    }
    MeshFileData data;
    ASSERT_EQ(readOffText(text, data), "") << keyword;
    expectPoints(data, unitSquare);
    expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 } });
  }
}

// Some writers leave out the keyword; numbers in every notation from_chars and writers use.
TEST(MeshFile, OffWithoutKeywordAndNumberNotations)
{
  MeshFileData data;
  ASSERT_EQ(readOffText("3 1 0\n+1.5 -2e-3 .25\n1E2 0 -0\n7 8 9\n3 0 1 2\n", data), "");
  expectPoints(data, { { 1.5, -2e-3, 0.25 }, { 100, 0, 0 }, { 7, 8, 9 } });
  expectTriangles(data, { { 0, 1, 2 } });
}

// ---- OBJ features

TEST(MeshFile, ObjPolygonsNegativeIndicesTexturesKept)
{
  MeshFileData data;
  ASSERT_EQ(readObjText(smallObj, data), "");
  expectPoints(data, { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0.5, 2, 0 } });
  expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 }, { 3, 2, 4 } });
  EXPECT_EQ(data.polygons, 1);
  EXPECT_EQ(data.format, "OBJ");
  ASSERT_EQ(data.textureCoordinates.size(), 5u);
  EXPECT_EQ(data.textureCoordinates[4].x, 0.5);
  EXPECT_EQ(data.textureCoordinates[4].y, 1.0);
  EXPECT_EQ(data.textureCoordinates[2].x, 1.0);
  EXPECT_EQ(data.texturedCornersIgnored, 0);
}

TEST(MeshFile, ObjCornerFormsStatementsCommentsCrlfContinuation)
{
  const std::string text = "# exported\r\n"
                           "o square\r\n"
                           "g group1\r\n"
                           "usemtl red\r\n"
                           "s off\r\n"
                           "v 0 0 0 1.0\r\n"         // w
                           "v 1 0 0 0.5 0.5 0.5\r\n" // colour
                           "v 1 1 0 # trailing comment\r\n"
                           "v \\\r\n" // continued
                           "  0 1 0\r\n"
                           "vn 0 0 1\r\n"
                           "vp 0.5\r\n"
                           "curv 0 1 2\r\n" // unknown statement
                           "l 1 2\r\n"
                           "p 3\r\n"
                           "\r\n"
                           "f 1//1 2//1 3//1\r\n"
                           "f 1//1 \\\n"
                           "3//1 4//1\n";
  MeshFileData data;
  ASSERT_EQ(readObjText(text, data), "");
  expectPoints(data, unitSquare);
  expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 } });
  EXPECT_TRUE(data.textureCoordinates.empty());
  EXPECT_EQ(data.texturedCornersIgnored, 0);
}

TEST(MeshFile, ObjTextureVertexNormalCorners)
{
  const std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                           "vt 0 0\nvt 1 0 0\nvt 1 1\nvt 0 1\nvt 1 1\nvn 0 0 1\n"
                           "f 1/1/1 2/2/1 3/3/1\n"
                           "f 1/1/1 3/5/1 4/4/1\n"; // vt 5 has vt 3's (u, v): no seam
  MeshFileData data;
  ASSERT_EQ(readObjText(text, data), "");
  expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 } });
  ASSERT_EQ(data.textureCoordinates.size(), 4u);
  EXPECT_EQ(data.textureCoordinates[3].x, 0.0);
  EXPECT_EQ(data.textureCoordinates[3].y, 1.0);
  EXPECT_EQ(data.texturedCornersIgnored, 0);
}

TEST(MeshFile, ObjSeamsDropTextureCoordinates)
{
  const std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.9 0.9\n"
                           "f 1/1 2/2 3/3\n"
                           "f 1/1 3/5 4/4\n"; // point 3 gets a second (u, v)
  MeshFileData data;
  ASSERT_EQ(readObjText(text, data), "");
  expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 } });
  EXPECT_TRUE(data.textureCoordinates.empty());
  EXPECT_EQ(data.texturedCornersIgnored, 1);
}

TEST(MeshFile, ObjMissingTextureCoordinatesDropThem)
{
  MeshFileData data;
  ASSERT_EQ(readObjText("v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", data), "");
  expectTriangles(data, { { 0, 1, 2 } });
  EXPECT_TRUE(data.textureCoordinates.empty());
  EXPECT_EQ(data.texturedCornersIgnored, 1);
}

// Corners without a vt leave their point at (0, 0); faces may precede their vertices.
TEST(MeshFile, ObjPartialTexturesAndForwardReferences)
{
  MeshFileData data;
  ASSERT_EQ(readObjText("f 1/1 2/2 3/2\nf 1 3 4\n"
                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0.5 0.5\nvt 1 1\n",
              data),
    "");
  expectPoints(data, unitSquare);
  expectTriangles(data, { { 0, 1, 2 }, { 0, 2, 3 } });
  ASSERT_EQ(data.textureCoordinates.size(), 4u);
  EXPECT_EQ(data.textureCoordinates[0].x, 0.5);
  EXPECT_EQ(data.textureCoordinates[2].y, 1.0);
  EXPECT_EQ(data.textureCoordinates[3].x, 0.0);
}

// ---- readMeshFile

TEST(MeshFile, FileExtensionsAndOpening)
{
  const std::filesystem::path folder = ::testing::TempDir();
  const std::filesystem::path upper = folder / "otparam_meshfile_test.OFF";
  std::ofstream(upper) << smallOff;
  MeshFileData data;
  EXPECT_EQ(readMeshFile(upper.string(), data), "");
  EXPECT_EQ(data.triangles.size(), 3u);
  std::filesystem::remove(upper);

  std::string error = readMeshFile((folder / "a.ply").string(), data);
  EXPECT_NE(error.find(".off, .obj"), std::string::npos) << error;
  EXPECT_TRUE(data.points.empty());
  error = readMeshFile((folder / "no_extension").string(), data);
  EXPECT_NE(error.find(".off, .obj"), std::string::npos) << error;
  error = readMeshFile((folder / "does_not_exist.obj").string(), data);
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
  const std::filesystem::path directory = folder / "otparam_meshfile_dir.obj";
  std::filesystem::create_directory(directory);
  error = readMeshFile(directory.string(), data);
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
  std::filesystem::remove(directory);
}

// ---- Errors

TEST(MeshFile, NonFiniteAndUnparsableCoordinates)
{
  for (const char* bad : { "nan", "inf", "-inf", "1e999", "1.0abc", "x", "1,5", "0x10" })
  {
    MeshFileData data;
    const std::string v = bad;
    expectError(readOffText("OFF\n3 1 0\n0 0 0\n0 " + v + " 0\n1 1 1\n3 0 1 2\n", data), data,
      "line 4: vertex 1 has a coordinate that is not a finite number");
    expectError(readObjText("v 0 0 0\n# c\nv 0 0 " + v + "\nv 1 1 1\nf 1 2 3\n", data), data,
      "line 3: vertex 2 has a coordinate that is not a finite number");
  }
  MeshFileData data;
  expectError(readOffText("OFF\n3 1 0\n0 0 0\n0 0\n1 1 1\n3 0 1 2\n", data), data,
    "line 4: vertex 1 has fewer than 3 coordinates");
  expectError(readObjText("v 0 0 0\nv 0 0 0\nvt nan 0\nf 1 2 3\n", data), data,
    "line 3: texture coordinate 1");
}

TEST(MeshFile, IndicesOutOfRange)
{
  std::string obj;
  for (int i = 0; i < 1000; ++i)
  {
    obj += "v " + std::to_string(i) + " 0 0\n";
  }
  MeshFileData data;
  expectError(readObjText(obj + "f 1 2 3\nf 1 2 1200\n", data), data,
    "line 1002: face refers to vertex 1200 but the file has 1000 vertices");
  expectError(readObjText(obj + "f 1 0 3\n", data), data, "line 1001: face refers to vertex 0");
  expectError(readObjText("v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n", data), data,
    "line 3: face refers to vertex -3 but only 2 vertices precede it");
  expectError(readObjText("f 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", data), data,
    "line 1: face refers to vertex 4 but the file has 3 vertices");
  expectError(readObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n", data), data,
    "line 4: face refers to vertex 99999999999");
  expectError(readOffText("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", data), data,
    "line 6: face refers to vertex 3 but the file has 3 vertices");
  expectError(readOffText("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", data), data,
    "line 6: face refers to vertex -1");
}

TEST(MeshFile, BadFaces)
{
  MeshFileData data;
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  expectError(readOffText(off + "2 0 1\n", data), data, "line 6: face has 2 corners");
  expectError(readOffText(off + "-1\n", data), data, "line 6: face has -1 corners");
  expectError(readOffText(off + "3 0 1 1\n", data), data, "line 6: face uses vertex 1 more");
  expectError(readOffText(off + "4 0 1\n", data), data, "line 6: face announces 4 corners");
  expectError(readOffText(off + "2000000000 0 1 2\n", data), data, "line 6: face announces");
  expectError(readOffText(off + "three 0 1 2\n", data), data, "line 6: face corner count");
  expectError(readOffText(off + "3 0 1 x\n", data), data, "line 6: face corner 'x'");
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expectError(readObjText(obj + "f 1 2\n", data), data, "line 4: face has 2 corners");
  expectError(readObjText(obj + "f\n", data), data, "line 4: face has 0 corners");
  expectError(readObjText(obj + "f 1 2 -2\n", data), data, "line 4: face uses vertex 2 more");
  expectError(readObjText(obj + "f 1 2 a\n", data), data, "line 4: face corner 'a'");
  expectError(readObjText(obj + "f 1 2 3/x\n", data), data, "line 4: face corner '3/x'");
  expectError(readObjText(obj + "f 1 2 3/0\n", data), data, "line 4: face corner '3/0'");
  expectError(readObjText(obj + "f 1 2 3/1/x\n", data), data, "line 4: face corner '3/1/x'");
  expectError(readObjText(obj + "f 1 2 3/1/1/1\n", data), data, "line 4");
  // Found by the fuzzer: -index overflowed, and the vertex became count + index as an int.
  expectError(readObjText(obj + "f 1 2 -9223372036854775808\n", data), data,
    "line 4: face refers to vertex -9223372036854775808 but only 3 vertices precede it");
  // The line of a continued statement is where it starts; lines stay physical lines.
  expectError(readObjText(obj + "f 1 \\\r\n2 \\\r\n3\r\nf 1 1 2\r\n", data), data, "line 7:");
}

TEST(MeshFile, OffCountsBeyondTheFile)
{
  std::string text = "OFF\n1000 1 0\n";
  for (int i = 0; i < 10; ++i)
  {
    text += "0 0 " + std::to_string(i) + "\n";
  }
  MeshFileData data;
  expectError(readOffText(text, data), data,
    "line 12: the header announces 1000 vertices but the file ends after 10");
  expectError(readOffText("OFF\n3 5 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", data), data,
    "line 6: the header announces 5 faces but the file ends after 1");
  // No reserve() from these: they would ask for gigabytes.
  expectError(readOffText("OFF\n2000000000 1 0\n", data), data,
    "line 2: the header announces 2000000000 vertices but the file ends after 0");
  expectError(readOffText("OFF\n3 2000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", data), data,
    "the header announces 2000000000 faces but the file ends after 1");
  expectError(readOffText("OFF\n9000000000000 1 0\n", data), data, "line 2: the header announces");
  expectError(readOffText("OFF 99999999999999999999999 1 0\n", data), data, "line 1: expected");
  expectError(readOffText("OFF\n-3 1 0\n", data), data, "line 2: negative count");
  expectError(readOffText("OFF\n3 -1 0\n", data), data, "line 2: negative count");
}

TEST(MeshFile, HeadersEmptyFilesNoFaces)
{
  MeshFileData data;
  expectError(
    readOffText("OFF BINARY\n3 1 0\n", data), data, "line 1: binary OFF is not supported");
  expectError(readOffText("OFF\nBINARY\n", data), data, "line 2: binary OFF is not supported");
  expectError(readOffText("PLY\n3 1 0\n", data), data, "line 1: expected the OFF header");
  expectError(readOffText("4OFF\n3 1 0\n", data), data, "line 1: expected the OFF header");
  expectError(readOffText("OFF\n3 faces\n", data), data, "line 2: expected the vertex and face");
  expectError(readOffText("", data), data, "line 1: no vertices");
  expectError(readOffText("\n# nothing\n\n", data), data, "line 3: no vertices");
  expectError(readOffText("OFF\n", data), data, "line 1: no vertices");
  expectError(readOffText("OFF\n0 0 0\n", data), data, "line 2: no vertices");
  expectError(readOffText("OFF 3 0 0\n0 0 0\n1 0 0\n0 1 0\n", data), data, "line 1: no faces");
  expectError(readObjText("", data), data, "line 1: no vertices");
  expectError(readObjText("# only\r\n# comments\r\n", data), data, "line 2: no vertices");
  expectError(readObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n", data), data, "line 4: no faces");
}

TEST(MeshFile, BinaryData)
{
  MeshFileData data;
  std::string off = std::string(smallOff);
  off[off.find("1 1 0")] = '\0';
  expectError(readOffText(off, data), data, "not a text OFF file (binary data at line 6)");
  std::string obj = std::string(smallObj);
  obj[obj.find("vt 1 1")] = '\x01';
  expectError(readObjText(obj, data), data, "not a text OBJ file (binary data at line 10)");
  // A stray NUL in a comment is binary too; the byte 0x7f also.
  expectError(readObjText("# \x7f\nv 0 0 0\n", data), data, "(binary data at line 1)");
}

TEST(MeshFile, ResultIsClearedOnError)
{
  MeshFileData data;
  ASSERT_EQ(readObjText(smallObj, data), "");
  ASSERT_FALSE(data.textureCoordinates.empty());
  EXPECT_NE(readObjText("v 0 0 0\nf 1 2 3\n", data), "");
  EXPECT_TRUE(data.points.empty() && data.triangles.empty() && data.textureCoordinates.empty());
  EXPECT_EQ(data.polygons, 0);
  EXPECT_EQ(data.format, "");
}

// ---- Hostile inputs

TEST(MeshFile, EveryPrefixOfAValidFile)
{
  for (const std::string text : { std::string(smallOff), std::string(smallObj) })
  {
    const bool off = text[0] == 'O';
    for (size_t length = 0; length <= text.size(); ++length)
    {
      MeshFileData data;
      const std::string prefix = text.substr(0, length);
      const std::string error = off ? readOffText(prefix, data) : readObjText(prefix, data);
      expectSane(error, data);
    }
  }
}

TEST(MeshFile, RandomJunk)
{
  std::mt19937 random(20240611);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<size_t> length(0, 3000);
  // Binary bytes, and text made of what mesh files are made of (reaches the parsers' depths).
  const std::string alphabet = "0123456789 .-+e/#\n\r\t\\vftnOFFCBINARY";
  std::uniform_int_distribution<size_t> letter(0, alphabet.size() - 1);
  for (int buffer = 0; buffer < 600; ++buffer)
  {
    std::string text(length(random), ' ');
    for (char& c : text)
    {
      c = buffer % 2 == 0 ? static_cast<char>(byte(random)) : alphabet[letter(random)];
    }
    if (buffer % 4 == 1)
    {
      text = std::string(buffer % 8 == 1 ? smallOff : smallObj) + text;
    }
    MeshFileData data;
    expectSane(readOffText(text, data), data);
    expectSane(readObjText(text, data), data);
  }
}

// A million lines in well under a second (an optimized build; sanitizers are slower).
TEST(MeshFile, MillionLines)
{
  const int n = 578; // n^2 vertices, 2 (n-1)^2 triangles: about 1e6 lines
  std::string obj, off;
  obj.reserve(40 << 20);
  off.reserve(40 << 20);
  off = "OFF\n" + std::to_string(n * n) + " " + std::to_string(2 * (n - 1) * (n - 1)) + " 0\n";
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const std::string xyz =
        std::to_string(i * 0.001) + " " + std::to_string(j * 0.001) + " 0.123456789\n";
      obj += "v " + xyz;
      off += xyz;
    }
  }
  for (int j = 0; j + 1 < n; ++j)
  {
    for (int i = 0; i + 1 < n; ++i)
    {
      const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      obj += "f " + std::to_string(a + 1) + " " + std::to_string(b + 1) + " " +
        std::to_string(c + 1) + "\nf " + std::to_string(a + 1) + " " + std::to_string(c + 1) + " " +
        std::to_string(d + 1) + "\n";
      off += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n3 " +
        std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
    }
  }
  for (const bool isOff : { false, true })
  {
    MeshFileData data;
    const auto start = std::chrono::steady_clock::now();
    const std::string error = isOff ? readOffText(off, data) : readObjText(obj, data);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(error, "");
    EXPECT_EQ(data.points.size(), static_cast<size_t>(n * n));
    EXPECT_EQ(data.triangles.size(), static_cast<size_t>(2 * (n - 1) * (n - 1)));
    std::cout << (isOff ? "OFF" : "OBJ") << ", " << data.points.size() + data.triangles.size()
              << " lines: " << seconds << " s\n";
#ifdef NDEBUG
    EXPECT_LT(seconds, 1.0);
#endif
  }
}
