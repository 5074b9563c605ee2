/**
 * @class   vtkOTParamMeshReader
 * @brief   Reads OFF and OBJ triangle surfaces as real files write them.
 *
 * VTK 9.2 has no OFF reader, and its vtkOBJReader crashes on faces that name texture indices
 * without any `vt` line (`f 1/1 15/15 16/16`), as many real files do. This reader takes both
 * formats the way real files write them: OFF (also COFF, NOFF, STOFF: extra per-vertex values and
 * face colours are ignored) and OBJ (corners `i`, `i/t`, `i//n`, `i/t/n`, negative indices,
 * missing `vt`/`vn` lines, groups and materials ignored), with comments, blank lines and CRLF.
 * Polygons are split into triangles (a fan from their first corner). The output has every
 * vertex of the file in file order (unreferenced ones too: the OTParam filters drop them), the
 * triangles, and, for an OBJ file whose `vt` give one texture coordinate per vertex, the point
 * array TextureCoordinates as the active texture coordinates. Field data:
 * PolygonsTriangulated (faces with more than 3 corners). A file that cannot be read is
 * reported with its line number and the output is left empty.
 */
#ifndef vtkOTParamMeshReader_h
#define vtkOTParamMeshReader_h

#include "OTParamFiltersModule.h" // for export macro
#include "vtkOTParamAlgorithm.h"

class OTPARAMFILTERS_EXPORT vtkOTParamMeshReader : public vtkOTParamAlgorithm
{
public:
  static vtkOTParamMeshReader* New();
  vtkTypeMacro(vtkOTParamMeshReader, vtkOTParamAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read (.off or .obj, any case).
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /**
   * 1 when the name ends in .off or .obj (any case): what ParaView asks before it offers the
   * reader.
   */
  static int CanReadFile(const char* fileName);

protected:
  vtkOTParamMeshReader();
  ~vtkOTParamMeshReader() override;

  int Execute(vtkInformationVector** inputVector, vtkInformationVector* outputVector) override;

  char* FileName = nullptr;

private:
  vtkOTParamMeshReader(const vtkOTParamMeshReader&) = delete;
  void operator=(const vtkOTParamMeshReader&) = delete;
};

#endif
