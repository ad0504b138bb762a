// A .vtu file's text for tests and fuzz targets that write one to disk: one tetrahedron.
// (Header only: the fuzz targets include it as "tests/support/vtu_text.h" without the test
// support library.)
#pragma once

namespace tsptest {

/// One tetrahedron (the unit corner, points 0..3) with point data f = 0, 1, 2, 3, all ascii.
inline constexpr char kOneTetVtu[] =
    "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">"
    "<UnstructuredGrid><Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">"
    "<PointData><DataArray type=\"Float32\" Name=\"f\" format=\"ascii\">0 1 2 3</DataArray>"
    "</PointData><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
    "0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points><Cells>"
    "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>"
    "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray>"
    "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10</DataArray>"
    "</Cells></Piece></UnstructuredGrid></VTKFile>";

}  // namespace tsptest
