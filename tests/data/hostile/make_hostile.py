#!/usr/bin/env python3
"""Writes the hostile-input fixtures (tests/data/hostile/README.md). Standard library only."""
import base64, os, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    mode = 'wb' if isinstance(data, bytes) else 'w'
    with open(os.path.join(HERE, name), mode) as f:
        f.write(data)


def vti_appended(name, extent, arrays_xml, payload, header='UInt32', compressor=''):
    comp = f' compressor="{compressor}"' if compressor else ''
    head = (f'<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0" '
            f'byte_order="LittleEndian" header_type="{header}"{comp}>\n'
            f'  <ImageData WholeExtent="{extent}" Origin="0 0 0" Spacing="1 1 1">\n'
            f'    <Piece Extent="{extent}">\n      <PointData Scalars="f">\n{arrays_xml}'
            '      </PointData>\n    </Piece>\n  </ImageData>\n'
            '  <AppendedData encoding="raw">\n   _').encode()
    write(name, head + payload + b'\n  </AppendedData>\n</VTKFile>\n')


# 1. A zlib header whose sizes wrap around 2^64 to exactly the expected 256 bytes: 3 blocks of
#    2^63 bytes, the last of 256; each block inflates to 64 KiB, far past the 256-byte array.
values = struct.pack('<64f', *range(64))
block = zlib.compress(b'\x00' * 65536)
header = struct.pack('<6Q', 3, 2**63, 256, len(block), len(block), len(block))
vti_appended('zlib_overflow.vti', '0 3 0 3 0 3',
             '        <DataArray type="Float32" Name="f" format="appended" offset="0"/>\n',
             header + block * 3, header='UInt64', compressor='vtkZLibDataCompressor')

# 2. Appended offsets that are not non-negative whole numbers.
plain = struct.pack('<I', 256) + values
for tag, offset in (('negative', '-1'), ('text', 'abc')):
    vti_appended(f'offset_{tag}.vti', '0 3 0 3 0 3',
                 f'        <DataArray type="Float32" Name="f" format="appended" '
                 f'offset="{offset}"/>\n', plain)

# 3. A WholeExtent of 2·10⁹ samples per axis with a tiny piece: refused before any allocation.
write('huge_extent.vti',
      '<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian">\n'
      '  <ImageData WholeExtent="0 2000000000 0 2000000000 0 2000000000" Origin="0 0 0" '
      'Spacing="1 1 1">\n    <Piece Extent="0 1 0 1 0 1">\n      <PointData Scalars="f">\n'
      '        <DataArray type="Float32" Name="f" format="ascii">0 1 2 3 4 5 6 7</DataArray>\n'
      '      </PointData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n')

# 4. A .pvd with NaN time steps (twice: NaN is not even equal to itself).
write('nan_timestep.pvd',
      '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
      '    <DataSet timestep="nan" file="../vti/ascii_0.vti"/>\n'
      '    <DataSet timestep="nan" file="../vti/ascii_1.vti"/>\n  </Collection>\n</VTKFile>\n')

# 5. Transfer functions with a number beyond the double range and with a NaN-like domain.
write('tf_1e400.json', '{"range": [0, 1e400], "points": [[0, 0, 0, 0, 0], [1, 1, 1, 1, 1]]}\n')
write('tf_inf_domain.json', '{"range": [-Infinity, 1], "points": [[0, 0, 0, 0, 0]]}\n')
