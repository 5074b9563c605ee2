// OFF and OBJ parsing one physical line at a time (std::getline into one buffer), tokens as
// string_views of that line, numbers by std::from_chars: iostream >> per token is several times
// slower on million-line files.
#include "Mesh/MeshFile.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <utility>

namespace otparam
{
namespace
{

// Reserving from a header's counts is capped: a hostile header must not allocate gigabytes.
constexpr long long ReserveCap = 1 << 20;
constexpr long long MaxVertices = INT_MAX; // Triangle holds ints

bool isBlank(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// Control characters other than whitespace never occur in a text mesh file (bytes >= 0x80 do:
// UTF-8 in comments and names).
bool isBinary(char c)
{
  const auto u = static_cast<unsigned char>(c);
  return (u < 0x20 && !isBlank(c)) || u == 0x7f;
}

std::string at(long long line, const std::string& message)
{
  return "line " + std::to_string(line) + ": " + message;
}

// A token in a message, shortened: a line can be megabytes long.
std::string quote(std::string_view text)
{
  constexpr size_t Shown = 32;
  return "'" + std::string(text.substr(0, Shown)) + (text.size() > Shown ? "...'" : "'");
}

class Tokens
{
public:
  explicit Tokens(std::string_view text)
    : Rest(text)
  {
  }
  // The next whitespace-separated token; false (and empty) at the end.
  bool next(std::string_view& token)
  {
    size_t begin = 0;
    while (begin < this->Rest.size() && isBlank(this->Rest[begin]))
    {
      ++begin;
    }
    size_t end = begin;
    while (end < this->Rest.size() && !isBlank(this->Rest[end]))
    {
      ++end;
    }
    token = this->Rest.substr(begin, end - begin);
    this->Rest.remove_prefix(end);
    return !token.empty();
  }
  std::string_view rest() const { return this->Rest; }

private:
  std::string_view Rest;
};

// from_chars refuses a leading '+', which some writers emit.
std::string_view withoutPlus(std::string_view token)
{
  if (token.size() > 1 && token[0] == '+' && token[1] != '+' && token[1] != '-')
  {
    token.remove_prefix(1);
  }
  return token;
}

// The whole token as a finite double (nan, inf and out-of-range values are not).
bool parseFinite(std::string_view token, double& value)
{
  token = withoutPlus(token);
  const char* end = token.data() + token.size();
  const auto [last, error] = std::from_chars(token.data(), end, value);
  return error == std::errc() && last == end && std::isfinite(value);
}

bool parseInteger(std::string_view token, long long& value)
{
  token = withoutPlus(token);
  const char* end = token.data() + token.size();
  const auto [last, error] = std::from_chars(token.data(), end, value);
  return error == std::errc() && last == end;
}

// x y z as the next three tokens; what follows (w, colours, normals) is not read. "" or what
// is wrong with the vertex.
std::string parseXYZ(Tokens& tokens, Vec3& p)
{
  for (double* coordinate : { &p.x, &p.y, &p.z })
  {
    std::string_view word;
    if (!tokens.next(word))
    {
      return "has fewer than 3 coordinates";
    }
    if (!parseFinite(word, *coordinate))
    {
      return "has a coordinate that is not a finite number";
    }
  }
  return "";
}

// Appends a face (corner point ids) fan-triangulated from its first corner; "" or why not.
// `base` turns ids into the file's numbering for the message.
std::string addFace(
  const std::vector<int>& corners, int base, std::vector<int>& scratch, MeshFileData& out)
{
  if (corners.size() < 3)
  {
    return "face has " + std::to_string(corners.size()) + " corners (at least 3 needed)";
  }
  scratch.assign(corners.begin(), corners.end());
  std::sort(scratch.begin(), scratch.end());
  const auto repeated = std::adjacent_find(scratch.begin(), scratch.end());
  if (repeated != scratch.end())
  {
    return "face uses vertex " + std::to_string(static_cast<long long>(*repeated) + base) +
      " more than once";
  }
  for (size_t k = 1; k + 1 < corners.size(); ++k)
  {
    out.triangles.push_back({ corners[0], corners[k], corners[k + 1] });
  }
  out.polygons += corners.size() > 3 ? 1 : 0;
  return "";
}

// Physical lines with their comment and trailing whitespace removed; stops at binary data.
class LineReader
{
public:
  LineReader(std::istream& in, const char* format)
    : In(in)
    , Format(format)
  {
  }
  // False at the end of the input or on binary data (then error() says so).
  bool next(std::string_view& content);
  // The next line that is not blank once its comment is removed.
  bool nextContent(std::string_view& content)
  {
    while (this->next(content))
    {
      if (!content.empty())
      {
        return true;
      }
    }
    return false;
  }
  long long number() const { return this->Number; }
  const std::string& error() const { return this->Error; }

private:
  std::istream& In;
  const char* Format;
  std::string Line;
  long long Number = 0;
  std::string Error;
};

bool LineReader::next(std::string_view& content)
{
  if (!this->Error.empty() || !std::getline(this->In, this->Line))
  {
    return false;
  }
  ++this->Number;
  std::string_view text(this->Line);
  if (this->Number == 1 && text.substr(0, 3) == "\xEF\xBB\xBF")
  {
    text.remove_prefix(3); // a UTF-8 byte order mark
  }
  if (std::any_of(text.begin(), text.end(), isBinary))
  {
    this->Error = std::string("not a text ") + this->Format + " file (binary data at line " +
      std::to_string(this->Number) + ")";
    return false;
  }
  text = text.substr(0, text.find('#'));
  while (!text.empty() && isBlank(text.back()))
  {
    text.remove_suffix(1);
  }
  content = text;
  return true;
}

// [ST][C][N]OFF: texture coordinates, colours and normals after x y z are ignored. 4OFF and
// nOFF (other dimensions) are not.
bool isOffKeyword(std::string_view word)
{
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF")
  {
    return false;
  }
  word.remove_suffix(3);
  for (std::string_view prefix : { "ST", "C", "N" })
  {
    if (word.substr(0, prefix.size()) == prefix)
    {
      word.remove_prefix(prefix.size());
    }
  }
  return word.empty();
}

class OffParser
{
public:
  OffParser(std::istream& in, MeshFileData& out)
    : Lines(in, "OFF")
    , Out(out)
  {
  }
  std::string run()
  {
    std::string error = this->readHeader();
    if (error.empty())
    {
      error = this->readVertices();
    }
    return error.empty() ? this->readFaces() : error;
  }

private:
  std::string readHeader();
  std::string readCounts(std::string_view counts);
  std::string readVertices();
  std::string readFaces();
  std::string readFace(std::string_view content);
  // Why the input stopped before `announced` items (binary data, or the end of the file).
  std::string endedEarly(const char* what, long long announced, size_t found) const
  {
    if (!this->Lines.error().empty())
    {
      return this->Lines.error();
    }
    return at(std::max(this->Lines.number(), 1LL),
      "the header announces " + std::to_string(announced) + " " + what +
        " but the file ends after " + std::to_string(found));
  }

  LineReader Lines;
  MeshFileData& Out;
  long long Vertices = 0;
  long long Faces = 0;
  std::vector<int> Corners;
  std::vector<int> Scratch;
};

std::string OffParser::readHeader()
{
  std::string_view content;
  if (!this->Lines.nextContent(content))
  {
    return this->Lines.error().empty()
      ? at(std::max(this->Lines.number(), 1LL), "no vertices (the file has no OFF header)")
      : this->Lines.error();
  }
  Tokens tokens(content);
  std::string_view word;
  tokens.next(word);
  long long count = 0;
  if (parseInteger(word, count))
  {
    return this->readCounts(content); // no keyword: some writers start with the counts
  }
  if (!isOffKeyword(word))
  {
    return at(this->Lines.number(),
      "expected the OFF header (OFF, COFF, NOFF, CNOFF, STOFF), found " + quote(word));
  }
  if (!tokens.rest().empty())
  {
    return this->readCounts(tokens.rest());
  }
  if (!this->Lines.nextContent(content))
  {
    return this->Lines.error().empty()
      ? at(this->Lines.number(), "no vertices (the header has no counts)")
      : this->Lines.error();
  }
  return this->readCounts(content);
}

// "vertices faces [edges]"; the edge count is not used.
std::string OffParser::readCounts(std::string_view counts)
{
  const long long line = this->Lines.number();
  Tokens tokens(counts);
  std::string_view vertices, faces;
  tokens.next(vertices);
  if (vertices == "BINARY")
  {
    return at(line, "binary OFF is not supported");
  }
  if (!parseInteger(vertices, this->Vertices) || !tokens.next(faces) ||
    !parseInteger(faces, this->Faces))
  {
    return at(line, "expected the vertex and face counts, found " + quote(counts));
  }
  if (this->Vertices < 0 || this->Faces < 0)
  {
    return at(line, "negative count in the header");
  }
  if (this->Vertices == 0)
  {
    return at(line, "no vertices");
  }
  if (this->Faces == 0)
  {
    return at(line, "no faces");
  }
  if (this->Vertices > MaxVertices)
  {
    return at(line,
      "the header announces " + std::to_string(this->Vertices) + " vertices, more than the " +
        std::to_string(MaxVertices) + " this reader supports");
  }
  return "";
}

std::string OffParser::readVertices()
{
  this->Out.points.reserve(static_cast<size_t>(std::min(this->Vertices, ReserveCap)));
  std::string_view content;
  while (static_cast<long long>(this->Out.points.size()) < this->Vertices)
  {
    if (!this->Lines.nextContent(content))
    {
      return this->endedEarly("vertices", this->Vertices, this->Out.points.size());
    }
    Tokens tokens(content);
    Vec3 p;
    const std::string problem = parseXYZ(tokens, p);
    if (!problem.empty())
    {
      return at(
        this->Lines.number(), "vertex " + std::to_string(this->Out.points.size()) + " " + problem);
    }
    this->Out.points.push_back(p);
  }
  return "";
}

std::string OffParser::readFaces()
{
  this->Out.triangles.reserve(static_cast<size_t>(std::min(this->Faces, ReserveCap)));
  std::string_view content;
  for (long long f = 0; f < this->Faces; ++f)
  {
    if (!this->Lines.nextContent(content))
    {
      return this->endedEarly("faces", this->Faces, static_cast<size_t>(f));
    }
    const std::string problem = this->readFace(content);
    if (!problem.empty())
    {
      return at(this->Lines.number(), problem);
    }
  }
  return ""; // what follows the last face (if anything) is not read
}

// "n i0 ... i{n-1}", then colour values (ignored).
std::string OffParser::readFace(std::string_view content)
{
  Tokens tokens(content);
  std::string_view word;
  tokens.next(word);
  long long n = 0;
  if (!parseInteger(word, n))
  {
    return "face corner count " + quote(word) + " is not a number";
  }
  if (n < 3)
  {
    return "face has " + std::to_string(n) + " corners (at least 3 needed)";
  }
  this->Corners.clear();
  for (long long k = 0; k < n; ++k)
  {
    long long index = 0;
    if (!tokens.next(word))
    {
      return "face announces " + std::to_string(n) + " corners but lists " + std::to_string(k);
    }
    if (!parseInteger(word, index))
    {
      return "face corner " + quote(word) + " is not a vertex index";
    }
    if (index < 0 || index >= this->Vertices)
    {
      return "face refers to vertex " + std::to_string(index) + " but the file has " +
        std::to_string(this->Vertices) + " vertices";
    }
    this->Corners.push_back(static_cast<int>(index));
  }
  return addFace(this->Corners, 0, this->Scratch, this->Out);
}

class ObjParser
{
public:
  ObjParser(std::istream& in, MeshFileData& out)
    : Lines(in, "OBJ")
    , Out(out)
  {
  }
  std::string run();

private:
  bool nextStatement(std::string_view& statement);
  std::string readStatement(std::string_view statement);
  std::string readVertex(Tokens& tokens);
  std::string readTextureCoordinate(Tokens& tokens);
  std::string readFace(Tokens& tokens);
  std::string readCorner(std::string_view corner);
  std::string resolveVertex(long long index, int& point);
  std::string readTextureIndex(std::string_view texture, int point);
  std::string checkForwardReferences() const;
  void keepTextureCoordinates();

  struct ForwardReference
  {
    long long line;
    long long index;
  };

  LineReader Lines;
  MeshFileData& Out;
  std::string Joined;          // a statement continued over several lines
  long long StatementLine = 0; // where the current statement starts
  std::vector<Vec2> TextureValues;
  // (point, 0-based vt index) of every corner that names a vt; the vt may be missing.
  std::vector<std::pair<int, long long>> TexturedCorners;
  // Positive indices beyond the vertices read so far, each larger than the one before: the
  // first that the final count does not reach is the first bad one in the file.
  std::vector<ForwardReference> Forward;
  std::vector<int> Corners;
  std::vector<int> Scratch;
};

std::string ObjParser::run()
{
  std::string_view statement;
  while (this->nextStatement(statement))
  {
    const std::string problem = this->readStatement(statement);
    if (!problem.empty())
    {
      return at(this->StatementLine, problem);
    }
  }
  if (!this->Lines.error().empty())
  {
    return this->Lines.error();
  }
  const long long last = std::max(this->Lines.number(), 1LL);
  if (this->Out.points.empty())
  {
    return at(last, "no vertices");
  }
  const std::string problem = this->checkForwardReferences();
  if (!problem.empty())
  {
    return problem;
  }
  if (this->Out.triangles.empty())
  {
    return at(last, "no faces");
  }
  this->keepTextureCoordinates();
  return "";
}

// The next statement, its continuation lines (trailing backslash) joined.
bool ObjParser::nextStatement(std::string_view& statement)
{
  std::string_view content;
  if (!this->Lines.next(content))
  {
    return false;
  }
  this->StatementLine = this->Lines.number();
  if (content.empty() || content.back() != '\\')
  {
    statement = content;
    return true;
  }
  this->Joined.clear();
  while (!content.empty() && content.back() == '\\')
  {
    content.remove_suffix(1);
    this->Joined.append(content);
    this->Joined.push_back(' ');
    if (!this->Lines.next(content))
    {
      if (!this->Lines.error().empty())
      {
        return false;
      }
      content = {}; // a backslash on the last line continues nothing
    }
  }
  this->Joined.append(content);
  statement = this->Joined;
  return true;
}

std::string ObjParser::readStatement(std::string_view statement)
{
  Tokens tokens(statement);
  std::string_view keyword;
  tokens.next(keyword);
  if (keyword == "v")
  {
    return this->readVertex(tokens);
  }
  if (keyword == "vt")
  {
    return this->readTextureCoordinate(tokens);
  }
  if (keyword == "f")
  {
    return this->readFace(tokens);
  }
  return ""; // vn, l, p, g, o, s, usemtl, mtllib, ...: nothing of the surface
}

std::string ObjParser::readVertex(Tokens& tokens)
{
  if (static_cast<long long>(this->Out.points.size()) >= MaxVertices)
  {
    return "more than the " + std::to_string(MaxVertices) + " vertices this reader supports";
  }
  Vec3 p;
  const std::string problem = parseXYZ(tokens, p);
  if (!problem.empty())
  {
    return "vertex " + std::to_string(this->Out.points.size() + 1) + " " + problem;
  }
  this->Out.points.push_back(p);
  return "";
}

// "vt u [v [w]]": v defaults to 0, w is not used.
std::string ObjParser::readTextureCoordinate(Tokens& tokens)
{
  std::string_view word;
  Vec2 uv;
  if (!tokens.next(word) || !parseFinite(word, uv.x) ||
    (tokens.next(word) && !parseFinite(word, uv.y)))
  {
    return "texture coordinate " + std::to_string(this->TextureValues.size() + 1) +
      " is not made of finite numbers";
  }
  this->TextureValues.push_back(uv);
  return "";
}

std::string ObjParser::readFace(Tokens& tokens)
{
  this->Corners.clear();
  std::string_view corner;
  while (tokens.next(corner))
  {
    const std::string problem = this->readCorner(corner);
    if (!problem.empty())
    {
      return problem;
    }
  }
  return addFace(this->Corners, 1, this->Scratch, this->Out);
}

// "i", "i/t", "i//n" or "i/t/n"; the normal is checked to be a number, nothing more.
std::string ObjParser::readCorner(std::string_view corner)
{
  const size_t slash = corner.find('/');
  long long index = 0;
  int point = 0;
  if (!parseInteger(corner.substr(0, slash), index))
  {
    return "face corner " + quote(corner) + " is not a vertex index";
  }
  std::string problem = this->resolveVertex(index, point);
  if (!problem.empty())
  {
    return problem;
  }
  this->Corners.push_back(point);
  if (slash == std::string_view::npos)
  {
    return "";
  }
  const std::string_view rest = corner.substr(slash + 1);
  const size_t secondSlash = rest.find('/');
  const std::string_view normal =
    secondSlash == std::string_view::npos ? std::string_view() : rest.substr(secondSlash + 1);
  long long normalIndex = 0;
  if (!normal.empty() && !parseInteger(normal, normalIndex))
  {
    return "face corner " + quote(corner) + " is not of the form i, i/t, i//n or i/t/n";
  }
  problem = this->readTextureIndex(rest.substr(0, secondSlash), point);
  return problem.empty() ? problem : "face corner " + quote(corner) + ": " + problem;
}

// The 0-based point of an OBJ index (1-based, or negative: relative to the vertices so far).
std::string ObjParser::resolveVertex(long long index, int& point)
{
  const long long count = static_cast<long long>(this->Out.points.size());
  if (index == 0)
  {
    return "face refers to vertex 0 (OBJ numbers vertices from 1)";
  }
  if (index < 0)
  {
    // Not -index > count: -index overflows for the smallest long long (found by the fuzzer:
    // "f -9223372036854775808 ..." then named vertex count + index, truncated to an int).
    if (index < -count)
    {
      return "face refers to vertex " + std::to_string(index) + " but only " +
        std::to_string(count) + " vertices precede it";
    }
    point = static_cast<int>(count + index);
    return "";
  }
  if (index > MaxVertices)
  {
    return "face refers to vertex " + std::to_string(index) + ", beyond the " +
      std::to_string(MaxVertices) + " vertices this reader supports";
  }
  if (index > count && (this->Forward.empty() || index > this->Forward.back().index))
  {
    this->Forward.push_back({ this->StatementLine, index }); // checked once every v is read
  }
  point = static_cast<int>(index - 1);
  return "";
}

// Records the corner's vt; a missing one is not an error (real files name vts they lack).
std::string ObjParser::readTextureIndex(std::string_view texture, int point)
{
  if (texture.empty())
  {
    return "";
  }
  long long index = 0;
  if (!parseInteger(texture, index) || index == 0)
  {
    return "the texture index is not a number from 1 or a negative one";
  }
  const long long count = static_cast<long long>(this->TextureValues.size());
  this->TexturedCorners.emplace_back(point, index > 0 ? index - 1 : count + index);
  return "";
}

std::string ObjParser::checkForwardReferences() const
{
  const long long count = static_cast<long long>(this->Out.points.size());
  for (const ForwardReference& reference : this->Forward)
  {
    if (reference.index > count)
    {
      return at(reference.line,
        "face refers to vertex " + std::to_string(reference.index) + " but the file has " +
          std::to_string(count) + " vertices");
    }
  }
  return "";
}

// One (u, v) per point when no corner contradicts another (same vt, or a vt of the same
// values) and none names a missing vt. A file without any vt line has no texture coordinates
// to lose: its texture indices are ignored silently (real files write them so).
void ObjParser::keepTextureCoordinates()
{
  if (this->TexturedCorners.empty() || this->TextureValues.empty())
  {
    return;
  }
  const long long textures = static_cast<long long>(this->TextureValues.size());
  std::vector<long long> chosen(this->Out.points.size(), -1);
  long long ignored = 0;
  for (const auto& [point, texture] : this->TexturedCorners)
  {
    long long& first = chosen[point];
    if (texture < 0 || texture >= textures)
    {
      ++ignored;
    }
    else if (first < 0)
    {
      first = texture;
    }
    else if (first != texture &&
      (this->TextureValues[first].x != this->TextureValues[texture].x ||
        this->TextureValues[first].y != this->TextureValues[texture].y))
    {
      ++ignored;
    }
  }
  this->Out.texturedCornersIgnored = static_cast<int>(std::min<long long>(ignored, INT_MAX));
  if (ignored > 0)
  {
    return;
  }
  this->Out.textureCoordinates.assign(this->Out.points.size(), Vec2());
  for (size_t p = 0; p < chosen.size(); ++p)
  {
    if (chosen[p] >= 0)
    {
      this->Out.textureCoordinates[p] = this->TextureValues[chosen[p]];
    }
  }
}

template <class Parser>
std::string readWith(std::istream& in, MeshFileData& out, const char* format)
{
  out = MeshFileData();
  const std::string error = Parser(in, out).run();
  if (error.empty())
  {
    out.format = format;
  }
  else
  {
    out = MeshFileData();
  }
  return error;
}

} // namespace

std::string readOFF(std::istream& in, MeshFileData& out)
{
  return readWith<OffParser>(in, out, "OFF");
}

std::string readOBJ(std::istream& in, MeshFileData& out)
{
  return readWith<ObjParser>(in, out, "OBJ");
}

std::string readMeshFile(const std::string& path, MeshFileData& out)
{
  out = MeshFileData();
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of("/\\");
  std::string extension =
    dot == std::string::npos || (slash != std::string::npos && dot < slash) ? "" : path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".off" && extension != ".obj")
  {
    return "cannot read '" + path + "': " +
      (extension.empty() ? "no file extension" : "unsupported extension '" + extension + "'") +
      " (supported: .off, .obj)";
  }
  std::error_code ignored;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ignored))
  {
    return "cannot open '" + path + "'";
  }
  return extension == ".off" ? readOFF(in, out) : readOBJ(in, out);
}

} // namespace otparam
