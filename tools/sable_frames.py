"""The frames of one Sable run, read from its XDMF index (<dir>/<prefix>.xmf) rather than by
globbing <prefix>_NNNNNN.h5: a directory may still hold frames of an earlier, longer run with
the same prefix, and the index lists exactly this run's. Imported by tools/bed_slices and
tools/drum_angle."""
import os
import xml.dom.minidom


def run_frames(outdir, prefix="sable", kind=None):
    """Paths of the run's frame files in time order; exits with a message when there is no index.
    kind "particles", "fluid" or "surface": only the frames that hold it (with
    -io_particle_interval and -io_fluid_interval apart, a frame may hold one kind only; the
    index then repeats a kind's latest frame at the times it lacks, and these repeats are not
    listed)."""
    index = os.path.join(outdir, prefix + ".xmf")
    if not os.path.exists(index):
        raise SystemExit("no index %s: the run wrote no frames there (-io_interval, -io_dir, -io_prefix)" % index)
    first = {}  # file -> the earliest time of a grid pointing into it
    for grid in xml.dom.minidom.parse(index).getElementsByTagName("Grid"):
        if grid.getAttribute("GridType") != "Uniform":
            continue
        if kind is not None and grid.getAttribute("Name") != kind:
            continue
        t = float(grid.getElementsByTagName("Time")[0].getAttribute("Value"))
        for item in grid.getElementsByTagName("DataItem"):
            if item.getAttribute("Format") != "HDF":
                continue
            name = item.firstChild.data.strip().split(":")[0]
            first[name] = min(t, first.get(name, t))
    files = sorted(first, key=lambda f: first[f])
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
