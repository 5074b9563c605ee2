#include "vtkOTParamMeshReader.h"

#include "Mesh/MeshFile.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cctype>
#include <string>

vtkStandardNewMacro(vtkOTParamMeshReader);

vtkOTParamMeshReader::vtkOTParamMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkOTParamMeshReader::~vtkOTParamMeshReader()
{
  this->SetFileName(nullptr);
}

void vtkOTParamMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

int vtkOTParamMeshReader::CanReadFile(const char* fileName)
{
  if (!fileName)
  {
    return 0;
  }
  std::string name(fileName);
  std::transform(name.begin(), name.end(), name.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  auto endsWith = [&](const char* suffix)
  {
    const std::string s(suffix);
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  return endsWith(".off") || endsWith(".obj") ? 1 : 0;
}

int vtkOTParamMeshReader::Execute(vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("No FileName is set.");
    return 0;
  }
  otparam::MeshFileData data;
  const std::string problem = otparam::readMeshFile(this->FileName, data);
  if (!problem.empty())
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": " << problem);
    return 0;
  }
  this->UpdateProgress(0.8);

  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(data.points.size()));
  for (size_t i = 0; i < data.points.size(); ++i)
  {
    const otparam::Vec3& p = data.points[i];
    points->SetPoint(static_cast<vtkIdType>(i), p.x, p.y, p.z);
  }
  vtkNew<vtkCellArray> triangles;
  triangles->AllocateExact(static_cast<vtkIdType>(data.triangles.size()),
    3 * static_cast<vtkIdType>(data.triangles.size()));
  for (const otparam::Triangle& t : data.triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    triangles->InsertNextCell(3, ids);
  }
  output->SetPoints(points);
  output->SetPolys(triangles);
  if (!data.textureCoordinates.empty())
  {
    vtkNew<vtkDoubleArray> tcoords;
    tcoords->SetName("TextureCoordinates");
    tcoords->SetNumberOfComponents(2);
    tcoords->SetNumberOfTuples(static_cast<vtkIdType>(data.textureCoordinates.size()));
    for (size_t i = 0; i < data.textureCoordinates.size(); ++i)
    {
      const otparam::Vec2& uv = data.textureCoordinates[i];
      tcoords->SetTypedTuple(static_cast<vtkIdType>(i), &uv.x);
    }
    output->GetPointData()->SetTCoords(tcoords);
  }
  vtkNew<vtkIntArray> polygons;
  polygons->SetName("PolygonsTriangulated");
  polygons->InsertNextValue(data.polygons);
  output->GetFieldData()->AddArray(polygons);
  if (data.texturedCornersIgnored > 0)
  {
    vtkWarningMacro(<< this->FileName << ": " << data.texturedCornersIgnored
                    << " face corner(s) name texture coordinates that cannot be kept one per "
                       "vertex (seams, or vt lines missing); the output has no texture "
                       "coordinates.");
  }
  return 1;
}
