"""The frames of one Sable run, read from its XDMF index (<dir>/<prefix>.xmf) rather than by
globbing <prefix>_NNNNNN.h5: a directory may still hold frames of an earlier, longer run with
the same prefix, and the index lists exactly this run's. Imported by tools/bed_slices and
tools/drum_angle."""
import os
import xml.dom.minidom


def run_frames(outdir, prefix="sable"):
    """Paths of the run's frame files in time order; exits with a message when there is no index."""
    index = os.path.join(outdir, prefix + ".xmf")
    if not os.path.exists(index):
        raise SystemExit("no index %s: the run wrote no frames there (-io_interval, -io_dir, -io_prefix)" % index)
    files = []
    for item in xml.dom.minidom.parse(index).getElementsByTagName("DataItem"):
        if item.getAttribute("Format") != "HDF":
            continue
        name = item.firstChild.data.strip().split(":")[0]
        if name not in files:
            files.append(name)
    return [os.path.join(outdir, f) for f in files]


def fluid_mesh(outdir, prefix="sable"):
    """The fluid grid of the run's index: (origin, spacing), each (x, y, z) in metres, or None when
    the run wrote no fluid. The frames store cell fields as [z, y, x] arrays; the index's
    ORIGIN_DXDYDZ geometry lists z, y, x as well."""
    index = os.path.join(outdir, prefix + ".xmf")
    for geo in xml.dom.minidom.parse(index).getElementsByTagName("Geometry"):
        if geo.getAttribute("GeometryType") != "ORIGIN_DXDYDZ":
            continue
        items = [[float(v) for v in d.firstChild.data.split()] for d in geo.getElementsByTagName("DataItem")]
        return tuple(items[0][::-1]), tuple(items[1][::-1])
    return None
