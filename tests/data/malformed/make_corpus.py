#!/usr/bin/python3
"""Writes the malformed-mesh corpus beside this script. Every file must be rejected by
fairshape's readers with a clear error (tests/unit/malformed_test.cpp) and never crash.
Each name says what is wrong with it."""
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
TRI = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"

def ply_header(fmt, nv, nf, vprops="property float x\nproperty float y\nproperty float z\n",
               flist="property list uchar int vertex_indices\n"):
    return (f"ply\nformat {fmt} 1.0\nelement vertex {nv}\n{vprops}"
            f"element face {nf}\n{flist}end_header\n").encode()

rng = random.Random(7)
garbage = bytes(rng.randrange(256) for _ in range(512))

CORPUS = {
    "empty.off": b"",
    "wrong_magic.off": b"PLY\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    "missing_counts.off": b"OFF\n",
    "truncated_vertices.off": b"OFF\n4 1 0\n0 0 0\n1 0 0\n",
    "truncated_faces.off": (TRI.replace("3 1 0", "3 2 0") + "3 0 1 2\n").encode(),
    "bad_number.off": b"OFF\n3 1 0\n0 0 abc\n1 0 0\n0 1 0\n3 0 1 2\n",
    "nan_coordinate.off": b"OFF\n3 1 0\n0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n",
    "inf_coordinate.off": b"OFF\n3 1 0\n0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n",
    "negative_count.off": b"OFF\n-3 1 0\n0 0 0\n",
    "absurd_count.off": b"OFF\n2000000000 2000000000 0\n0 0 0\n",
    "face_index_out_of_range.off": (TRI + "3 0 1 7\n").encode(),
    "face_negative_index.off": (TRI + "3 0 -1 2\n").encode(),
    "face_two_vertices.off": (TRI + "2 0 1\n").encode(),
    "face_size_mismatch.off": (TRI + "4 0 1 2\n").encode(),
    "vertex_two_coordinates.off": b"OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    "repeated_vertex.off": b"OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 1 2\n",
    "nonmanifold_edge.off": b"OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n",
    "nonmanifold_vertex_bowtie.off": b"OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n-1 0 0\n-1 -1 0\n3 0 1 2\n3 0 3 4\n",
    "inconsistent_orientation.off": b"OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n",
    "binary_garbage.off": garbage,
    "no_faces.off": b"OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n",
    "index_zero.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
    "index_out_of_range.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
    "negative_index_out_of_range.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n",
    "bad_coordinate.obj": b"v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n",
    "face_two_vertices.obj": b"v 0 0 0\nv 1 0 0\nf 1 2\n",
    "vertex_two_coordinates.obj": b"v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "nan_coordinate.obj": b"v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "face_before_vertices.obj": b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n",
    "huge_index.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
    "only_vertices.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\n",
    # OpenSubdiv's sharpness tags: an edge the mesh does not have, a negative sharpness,
    # a corner on a vertex that does not exist, counts that do not match the values.
    "crease_missing_edge.obj": b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt crease 2/1/0 0 2 3.0\n",
    "crease_negative_sharpness.obj": b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt crease 2/1/0 0 1 -1\n",
    "corner_missing_vertex.obj": b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt corner 1/1/0 7 2.0\n",
    "crease_bad_counts.obj": b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt crease 2/1/0 0 1\n",
    "binary_garbage.obj": b"v " + garbage,
    "nonmanifold_vertex_double_cone.obj": (
        b"v 0 0 0\nv 1 0 1\nv -1 1 1\nv -1 -1 1\nv 1 0 -1\nv -1 1 -1\nv -1 -1 -1\n"
        b"f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\nf 1 6 5\nf 1 7 6\nf 1 5 7\nf 5 6 7\n"),
    "empty.ply": b"",
    "no_end_header.ply": b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
    "bad_format.ply": b"ply\nformat binary_middle_endian 1.0\nend_header\n",
    "bad_property_type.ply": b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n0\n",
    "property_before_element.ply": b"ply\nformat ascii 1.0\nproperty float x\nend_header\n",
    "missing_xyz.ply": ply_header("ascii", 3, 1, vprops="property float x\nproperty float y\n")
        + b"0 0\n1 0\n0 1\n3 0 1 2\n",
    "ascii_truncated.ply": ply_header("ascii", 3, 1) + b"0 0 0\n1 0 0\n",
    "ascii_index_out_of_range.ply": ply_header("ascii", 3, 1) + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n",
    "binary_truncated.ply": ply_header("binary_little_endian", 3, 1) + struct.pack("<3f", 0, 0, 0),
    "binary_absurd_count.ply": ply_header("binary_little_endian", 2000000000, 1) + struct.pack("<3f", 0, 0, 0),
    "binary_absurd_list_length.ply": ply_header("binary_little_endian", 3, 1,
                                                flist="property list int int vertex_indices\n")
        + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<i", 2000000000),
    "binary_nan.ply": ply_header("binary_little_endian", 3, 1)
        + struct.pack("<9f", 0, 0, float("nan"), 1, 0, 0, 0, 1, 0) + struct.pack("<B3i", 3, 0, 1, 2),
    "not_a_mesh.stl": b"solid x\nendsolid x\n",
}

if __name__ == "__main__":
    for name, data in CORPUS.items():
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode())
    print(f"wrote {len(CORPUS)} malformed files")
