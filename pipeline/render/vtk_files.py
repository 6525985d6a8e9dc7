"""VTK XML files (.vtp, .vtu) written through memory.

VTK's own file output aborts the whole process (`free(): invalid pointer`, SIGABRT) when the disk
fills during a write: no message, and a temporary folder left behind. So the XML is built in
memory by the same writer and settings pyvista uses (binary, zlib; the bytes of `mesh.save`),
and written by Python atomically: a full disk is then an OSError (ENOSPC) like any other, and
the stage's temporary folder is removed on the way out.
"""

from __future__ import annotations

from pathlib import Path

from ..staging.artefacts import atomic_write_bytes


def save_xml(mesh, path: Path) -> None:
    """Write the pyvista PolyData (.vtp) or UnstructuredGrid (.vtu) `mesh` to `path`."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter, vtkXMLUnstructuredGridWriter

    path = Path(path)
    writers = {".vtp": vtkXMLPolyDataWriter, ".vtu": vtkXMLUnstructuredGridWriter}
    if path.suffix not in writers:
        raise ValueError(f"{path}: VTK XML files here are .vtp or .vtu")
    writer = writers[path.suffix]()
    writer.SetInputData(mesh)
    writer.SetDataModeToBinary()  # base64 inline: the output string is ASCII text
    writer.SetCompressorTypeToZLib()
    writer.SetWriteToOutputString(True)
    if writer.Write() != 1:
        raise RuntimeError(f"VTK could not serialise {path.name}")
    atomic_write_bytes(path, writer.GetOutputString().encode("ascii"))
