"""Read deal.II's .vtu files with the standard library only: their
DataArrays are zlib-compressed and base64-encoded. Shared by the checkers
of tests/cli."""
import base64
import re
import struct
import zlib


def vtu_arrays(path):
    """Every DataArray of a deal.II .vtu file, by name, as a flat list."""
    text = open(path).read()
    arrays = {}
    for m in re.finditer(r'<DataArray([^>]*)>\s*([^<]*)</DataArray>', text):
        attributes, data = m.group(1), m.group(2).strip()
        name = re.search(r'Name="([^"]*)"', attributes)
        kind = re.search(r'type="([^"]*)"', attributes).group(1)
        # A 16-byte header (blocks, block size, last block size, compressed
        # size) in 24 base64 characters, then the compressed bytes.
        raw = zlib.decompress(base64.b64decode(data[24:]))
        code = {'Float32': 'f', 'Float64': 'd', 'Int32': 'i',
                'UInt8': 'B', 'Int64': 'q', 'UInt32': 'I'}[kind]
        arrays[name.group(1) if name else 'points'] = struct.unpack(
            '<%d%s' % (len(raw) // struct.calcsize(code), code), raw)
    return arrays
