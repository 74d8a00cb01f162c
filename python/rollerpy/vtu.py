"""The VTU and PVD files of a roller run (docs/scenes.md, Outputs) into numpy arrays: every
DataArray of a step_NNNN.vtu decoded and checked against its piece (decode_vtu, VtuError for a
malformed file), the mesh and fields of a step (read_vtu), the steps and times of fields.pvd; and
a small VTU written as roller writes it, for the scanners' self-checks and the tests."""
import base64
import binascii
import os
import re
import xml.etree.ElementTree as ET
import zlib
from dataclasses import dataclass

import numpy as np


class VtuError(Exception):
    """A VTU file (or one of its arrays) that cannot be decoded or contradicts its piece."""


VTK_TYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "<i2", "UInt16": "<u2", "Int32": "<i4", "UInt32": "<u4",
             "Int64": "<i8", "UInt64": "<u8", "Float32": "<f4", "Float64": "<f8"}
HEADER_TYPES = {"UInt32": "<u4", "UInt64": "<u8"}


def b64decode(text, what):
    try:
        return base64.b64decode(text, validate=True)
    except (binascii.Error, ValueError) as e:
        raise VtuError("%s: bad base64 (%s)" % (what, e))


def decode_binary(text, header_dtype, compressed, what):
    """The payload bytes of one inline format="binary" DataArray as vtu_writer.cpp writes it:
    uncompressed, base64 of [byte count][payload]; compressed, base64 of the header [number of
    blocks, block size, size of the last partial block (0 if full), compressed size of each block]
    followed by base64 of the deflated blocks."""
    text = re.sub(r"\s+", "", text or "")
    h = np.dtype(header_dtype).itemsize
    if not compressed:
        raw = b64decode(text, what)
        if len(raw) < h:
            raise VtuError("%s: %d bytes, shorter than its header" % (what, len(raw)))
        n = int(np.frombuffer(raw[:h], header_dtype)[0])
        if len(raw) - h != n:
            raise VtuError("%s: header says %d bytes, %d follow" % (what, n, len(raw) - h))
        return raw[h:]
    first_chars = 4 * ((h + 2) // 3)
    n_blocks = int(np.frombuffer(b64decode(text[:first_chars], what)[:h], header_dtype)[0])
    if n_blocks > len(text):
        raise VtuError("%s: %d blocks in a %d-character array" % (what, n_blocks, len(text)))
    header_bytes = h * (3 + n_blocks)
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = b64decode(text[:header_chars], what)[:header_bytes]
    if len(header) < header_bytes:
        raise VtuError("%s: compression header cut short" % what)
    header = [int(v) for v in np.frombuffer(header, header_dtype)]
    block_size, last_size, sizes = header[1], header[2], header[3:]
    data = b64decode(text[header_chars:], what)
    if sum(sizes) != len(data):
        raise VtuError("%s: compressed block sizes sum to %d bytes, %d follow" % (what, sum(sizes), len(data)))
    out, pos = [], 0
    for b, size in enumerate(sizes):
        try:
            block = zlib.decompress(data[pos:pos + size])
        except zlib.error as e:
            raise VtuError("%s: block %d does not inflate (%s)" % (what, b, e))
        expected = last_size if b == n_blocks - 1 and last_size else block_size
        if len(block) != expected:
            raise VtuError("%s: block %d inflates to %d bytes, expected %d" % (what, b, len(block), expected))
        out.append(block)
        pos += size
    return b"".join(out)


def decode_vtu(path):
    """Every DataArray of an UnstructuredGrid VTU file as (section, name, numpy array of shape
    (tuples, components)); raises VtuError when the file is malformed."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise VtuError("not XML (%s)" % e)
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        raise VtuError("not a VTKFile of type UnstructuredGrid")
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        raise VtuError("byte_order %s" % root.get("byte_order"))
    header_dtype = HEADER_TYPES.get(root.get("header_type", "UInt32"))
    if header_dtype is None:
        raise VtuError("header_type %s" % root.get("header_type"))
    compressor = root.get("compressor")
    if compressor not in (None, "vtkZLibDataCompressor"):
        raise VtuError("compressor %s" % compressor)
    pieces = root.findall("UnstructuredGrid/Piece")
    if not pieces:
        raise VtuError("no UnstructuredGrid/Piece")
    arrays = [("FieldData", a.get("Name", ""), np.array((a.text or "").split(), dtype=float).reshape(1, -1))
              for a in root.findall("UnstructuredGrid/FieldData/DataArray")]
    for k, piece in enumerate(pieces):
        try:
            n_points = int(piece.get("NumberOfPoints"))
            n_cells = int(piece.get("NumberOfCells"))
        except (TypeError, ValueError):
            raise VtuError("piece %d: NumberOfPoints/NumberOfCells missing or not integers" % k)
        counts = {"PointData": n_points, "CellData": n_cells, "Points": n_points, "Cells": n_cells}
        decoded = {}
        for section in ("PointData", "CellData", "Points", "Cells"):
            for node in piece.findall(section):
                for array in node.findall("DataArray"):
                    name = array.get("Name", "")
                    what = "%s/%s" % (section, name)
                    dtype = VTK_TYPES.get(array.get("type"))
                    if dtype is None:
                        raise VtuError("%s: type %s" % (what, array.get("type")))
                    fmt = array.get("format")
                    if fmt == "binary":
                        raw = decode_binary(array.text, header_dtype, compressor is not None, what)
                        if len(raw) % np.dtype(dtype).itemsize:
                            raise VtuError("%s: %d bytes, not a whole number of %s" % (
                                what, len(raw), array.get("type")))
                        values = np.frombuffer(raw, dtype)
                    elif fmt == "ascii":
                        try:
                            values = np.array((array.text or "").split(), dtype=float).astype(dtype)
                        except ValueError as e:
                            raise VtuError("%s: %s" % (what, e))
                    else:
                        raise VtuError("%s: format=%s is not decoded by this scanner (roller writes inline "
                                       "binary)" % (what, fmt))
                    nc = int(array.get("NumberOfComponents", "1"))
                    if nc < 1:
                        raise VtuError("%s: NumberOfComponents %d" % (what, nc))
                    if section == "Cells" and name == "connectivity":
                        n_tuples = None  # checked against the offsets below
                    else:
                        n_tuples = counts[section]
                    if n_tuples is not None and values.size != n_tuples * nc:
                        raise VtuError("%s: %d values, expected %d (%d tuples x %d components)" % (
                            what, values.size, n_tuples * nc, n_tuples, nc))
                    if values.size % nc:
                        raise VtuError("%s: %d values for %d components" % (what, values.size, nc))
                    decoded[(section, name)] = values
                    arrays.append((section, name, values.reshape(-1, nc)))
        points = [v for (s, _), v in decoded.items() if s == "Points"]
        if len(points) != 1 or points[0].size != 3 * n_points:
            raise VtuError("piece %d: no Points array of %d x 3 values" % (k, n_points))
        conn, offsets = decoded.get(("Cells", "connectivity")), decoded.get(("Cells", "offsets"))
        if conn is None or offsets is None or ("Cells", "types") not in decoded:
            raise VtuError("piece %d: Cells without connectivity, offsets and types" % k)
        if n_cells and (np.any(np.diff(offsets) < 0) or offsets[0] < 0 or int(offsets[-1]) != conn.size):
            raise VtuError("piece %d: offsets do not partition the %d connectivity entries" % (k, conn.size))
        if conn.size and (conn.min() < 0 or conn.max() >= n_points):
            raise VtuError("piece %d: connectivity refers to points outside 0..%d" % (k, n_points - 1))
    return arrays


@dataclass
class Vtu:
    """One step's mesh and fields: points (the deformed positions, x and y), the reference
    positions the file holds (roller writes the reference configuration and the displacement:
    ParaView's Warp By Vector), the elements as arrays of point indices, the point and cell data by
    name (one column per component; a one-component array is one-dimensional) and the file's field
    data (step, pass, time)."""
    points: np.ndarray
    elements: list
    point_data: dict
    cell_data: dict
    reference: np.ndarray = None
    field_data: dict = None


def _squeezed(values):
    return values[:, 0] if values.shape[1] == 1 else values


def read_vtu(path):
    """A step_NNNN.vtu file as a Vtu (its first piece); raises VtuError when it is malformed."""
    arrays = decode_vtu(path)
    section = {}
    for where, name, values in arrays:
        section.setdefault(where, {}).setdefault(name, values)
    stored = next(iter(section["Points"].values()))[:, :2]
    conn = section["Cells"]["connectivity"][:, 0].astype(int)
    offsets = section["Cells"]["offsets"][:, 0].astype(int)
    elements = [conn[start:end] for start, end in zip(np.concatenate([[0], offsets[:-1]]), offsets)]
    point_data = {k: _squeezed(v) for k, v in section.get("PointData", {}).items()}
    field_data = {k: v[0, 0] if v.size == 1 else v[0] for k, v in section.get("FieldData", {}).items()}
    # Files with field data hold the reference configuration; older ones the deformed one.
    if "step" in field_data:
        reference, points = stored, stored + point_data["displacement"][:, :2]
    else:
        reference, points = stored - point_data["displacement"][:, :2], stored
    return Vtu(points=points, elements=elements, point_data=point_data,
               cell_data={k: _squeezed(v) for k, v in section.get("CellData", {}).items()},
               reference=reference, field_data=field_data)


def vtu_path(out, step):
    return os.path.join(out, "step_%04d.vtu" % step)


def available_steps(out):
    """The steps that have a step_NNNN.vtu in OUT, sorted (a stationary pass's loaded state,
    step_NNNN_loaded.vtu, is not a step of its own)."""
    return sorted(int(f[5:9]) for f in os.listdir(out) if re.fullmatch(r"step_\d{4}\.vtu", f))


def step_times(out):
    """Time of each step from OUT/fields.pvd ({} when the file is missing)."""
    path = os.path.join(out, "fields.pvd")
    if not os.path.exists(path):
        return {}
    return {int(d.get("file")[5:9]): float(d.get("timestep")) for d in ET.parse(path).getroot().iter("DataSet")
            if re.fullmatch(r"step_\d{4}\.vtu", d.get("file"))}


def reference_mesh(out):
    """The undeformed node positions and elements (a run restarted from another's state starts
    displaced already)."""
    step0 = read_vtu(vtu_path(out, 0))
    return step0.reference, step0.elements


def top_nodes(points):
    """Indices of the nodes on the strip's top surface."""
    return np.where(np.abs(points[:, 1] - points[:, 1].max()) < 1e-9 * (1 + points[:, 1].max()))[0]


def triangles(elements):
    """The elements as triangles (a Q4 split into two), for matplotlib's Triangulation."""
    tris = []
    for e in elements:
        tris.append(e[:3])
        if len(e) == 4:
            tris.append([e[0], e[2], e[3]])
    return np.array(tris)


def encode_vtu_array(values, compressed, block=32768):
    """A Float64/Int64/UInt8 array encoded as vtu_writer.cpp does (the self-check's planted files)."""
    payload = np.ascontiguousarray(values).tobytes()
    if not compressed:
        return base64.b64encode(np.uint64(len(payload)).tobytes() + payload).decode()
    blocks = [zlib.compress(payload[i:i + block], 1) for i in range(0, len(payload), block)]
    header = [len(blocks), block, len(payload) % block] + [len(b) for b in blocks]
    return (base64.b64encode(np.array(header, "<u8").tobytes()).decode() +
            base64.b64encode(b"".join(blocks)).decode())


def write_test_vtu(path, displacement, compressed):
    """A two-triangle VTU in roller's layout with the given 4 x 2 point data."""
    def array(vtk_type, name, values, nc=None):
        attrs = ' NumberOfComponents="%d"' % nc if nc else ""
        return '        <DataArray type="%s" Name="%s"%s format="binary">\n          %s\n        </DataArray>\n' % (
            vtk_type, name, attrs, encode_vtu_array(values, compressed))
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "<f8")
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian"'
                ' header_type="UInt64"%s>\n  <UnstructuredGrid>\n    <Piece NumberOfPoints="4" NumberOfCells="2">\n'
                % (' compressor="vtkZLibDataCompressor"' if compressed else ""))
        f.write("      <PointData>\n" + array("Float64", "displacement", np.asarray(displacement, "<f8"), 2) +
                "      </PointData>\n      <CellData>\n" + array("Float64", "stress", np.zeros((2, 4), "<f8"), 4) +
                "      </CellData>\n      <Points>\n" + array("Float64", "Points", points, 3) + "      </Points>\n"
                "      <Cells>\n" + array("Int64", "connectivity", np.array([0, 1, 2, 0, 2, 3], "<i8")) +
                array("Int64", "offsets", np.array([3, 6], "<i8")) + array("UInt8", "types", np.array([5, 5], "u1")) +
                "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n")
