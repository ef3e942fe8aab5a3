#!/usr/bin/python3
"""DICOM RT structure sets written with pydicom (an independent writer) from known contours.

    make_rtstruct.py roundtrip OUTDIR [--points N] [--spacing MM]
        OUTDIR/rtstruct.dcm: two ROIs ("Outer Ellipsoid", "Inner Ellipsoid"), each an ellipsoid cut by
        parallel oblique planes (normal tilted 20 degrees off z), plus an empty ROI and a POINT marker;
        OUTDIR/truth.json: the exact contours (mm, LPS) before ContourData's decimal strings rounded them,
        and each ellipsoid's volume.
    make_rtstruct.py check CONTOURS.json TRUTH.json
        compares contours read back (contour4d extract's JSON) with the truth: every contour found, point
        for point; prints {"max_error_mm": ..., "contours": ...} and exits 1 above 0.001 mm.
    make_rtstruct.py corpus OUTDIR
        the malformed-input corpus (tests/corpus/rtstruct): bad_NN_* files that must fail with exit code NN
        and good_* seeds, each a few kB.

Coordinates are DICOM patient space (LPS), mm. UIDs are derived from fixed strings: the files are the same
bytes on every run.
"""
import argparse
import json
import math
import sys
import warnings

import numpy as np
import pydicom
from pydicom.dataset import Dataset, FileMetaDataset
from pydicom.sequence import Sequence
from pydicom.uid import ExplicitVRLittleEndian, ImplicitVRLittleEndian, generate_uid

RTSTRUCT_CLASS = "1.2.840.10008.5.1.4.1.1.481.3"
CT_CLASS = "1.2.840.10008.5.1.4.1.1.2"


def uid(name):
    return generate_uid(entropy_srcs=["contour4d-test", name])


def ds_text(v):
    """A decimal string of at most 16 characters (DICOM DS), 6 decimals."""
    s = f"{v:.6f}"
    return s if len(s) <= 16 else f"{v:.9g}"


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def plane_axes(normal):
    n = unit(normal)
    a = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = unit(np.cross(a, n))
    return u, np.cross(n, u)


def ellipsoid_section(center, axes, normal, offset, points):
    """The ellipse where the plane {p : n.p = offset} cuts the ellipsoid ((p - c) / axes)^2 = 1, or None."""
    n = unit(normal)
    u, v = plane_axes(n)
    A = np.diag(1.0 / np.asarray(axes, dtype=float) ** 2)
    o = n * offset - np.asarray(center, dtype=float)  # plane origin relative to the centre
    B = np.stack([u, v], axis=1)  # 3x2
    M = B.T @ A @ B
    b = B.T @ A @ o
    c0 = o @ A @ o - 1.0
    w = -np.linalg.solve(M, b)
    k = b @ np.linalg.solve(M, b) - c0
    vals, vecs = np.linalg.eigh(M)
    if k <= 0 or math.sqrt(k / vals.max()) < 1.0:  # no section, or one under 1 mm across
        return None
    t = np.linspace(0.0, 2.0 * math.pi, points, endpoint=False)
    circle = np.stack([np.cos(t), np.sin(t)], axis=1) * math.sqrt(k)
    st = w + (circle / np.sqrt(vals)) @ vecs.T
    return (np.asarray(center) + o)[None, :] + st @ B.T


def ellipsoid_stack(center, axes, normal, spacing, points):
    n = unit(normal)
    reach = float(np.linalg.norm(np.asarray(axes) * n))  # support of the ellipsoid along n
    c = float(n @ np.asarray(center))
    out = []
    k = math.ceil((c - reach) / spacing)  # planes n.p = k * spacing: every shape of one normal shares them
    while k * spacing < c + reach:
        sec = ellipsoid_section(center, axes, n, k * spacing, points)
        if sec is not None and len(sec) >= 3:
            out.append(sec)
        k += 1
    return out


# ----- the structure set ---------------------------------------------------------------------------------


def base_dataset(sop_class, modality, name):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = sop_class
    meta.MediaStorageSOPInstanceUID = uid(name + "-instance")
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    meta.ImplementationClassUID = uid("implementation")
    ds = Dataset()
    ds.file_meta = meta
    ds.preamble = b"\0" * 128
    ds.SpecificCharacterSet = "ISO_IR 100"
    ds.SOPClassUID = sop_class
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.StudyDate = "20240101"
    ds.Modality = modality
    ds.PatientName = "Phantom^Ellipsoid"
    ds.PatientID = "C4D-TEST"
    ds.StudyInstanceUID = uid("study")
    ds.SeriesInstanceUID = uid(name + "-series")
    ds.FrameOfReferenceUID = uid("frame-of-reference")
    return ds


def referenced_frame_of_reference(image_uids):
    images = Sequence()
    for u in image_uids:
        it = Dataset()
        it.ReferencedSOPClassUID = CT_CLASS
        it.ReferencedSOPInstanceUID = u
        images.append(it)
    series = Dataset()
    series.SeriesInstanceUID = uid("ct-series")
    series.ContourImageSequence = images
    study = Dataset()
    study.ReferencedSOPClassUID = "1.2.840.10008.3.1.2.3.1"
    study.ReferencedSOPInstanceUID = uid("study")
    study.RTReferencedSeriesSequence = Sequence([series])
    ref = Dataset()
    ref.FrameOfReferenceUID = uid("frame-of-reference")
    ref.RTReferencedStudySequence = Sequence([study])
    return ref


def contour_item(points, kind="CLOSED_PLANAR", number=None, image_uid=None):
    c = Dataset()
    if image_uid:
        img = Dataset()
        img.ReferencedSOPClassUID = CT_CLASS
        img.ReferencedSOPInstanceUID = image_uid
        c.ContourImageSequence = Sequence([img])
    if kind is not None:
        c.ContourGeometricType = kind
    c.NumberOfContourPoints = number if number is not None else len(points)
    c.ContourData = [ds_text(x) for p in points for x in p]
    return c


def rtstruct(name, rois, image_uids=(), with_references=True):
    """rois: list of dicts {number, name, contours: [points | (points, kind)], type, for_uid}."""
    ds = base_dataset(RTSTRUCT_CLASS, "RTSTRUCT", name)
    ds.StructureSetLabel = "C4D"
    ds.StructureSetDate = "20240101"
    if with_references:
        ds.ReferencedFrameOfReferenceSequence = Sequence([referenced_frame_of_reference(image_uids)])
    ssroi, roic, obs = Sequence(), Sequence(), Sequence()
    for r in rois:
        s = Dataset()
        s.ROINumber = r["number"]
        s.ReferencedFrameOfReferenceUID = r.get("for_uid", uid("frame-of-reference"))
        s.ROIName = r["name"]
        s.ROIGenerationAlgorithm = "MANUAL"
        ssroi.append(s)
        if r.get("contours") is not None:
            rc = Dataset()
            rc.ReferencedROINumber = r["number"]
            rc.ROIDisplayColor = [255, 0, 0]
            items = Sequence()
            for k, c in enumerate(r["contours"]):
                pts, kind = c if isinstance(c, tuple) else (c, "CLOSED_PLANAR")
                image = image_uids[k % len(image_uids)] if image_uids else None
                items.append(contour_item(pts, kind, image_uid=image))
            if items or r.get("empty_sequence"):
                rc.ContourSequence = items
            roic.append(rc)
        o = Dataset()
        o.ObservationNumber = r["number"]
        o.ReferencedROINumber = r["number"]
        o.RTROIInterpretedType = r.get("type", "ORGAN")
        o.ROIInterpreter = ""
        obs.append(o)
    ds.StructureSetROISequence = ssroi
    ds.ROIContourSequence = roic
    ds.RTROIObservationsSequence = obs
    return ds


def ct_image(name):
    ds = base_dataset(CT_CLASS, "CT", name)
    ds.ImagePositionPatient = ["0", "0", "0"]
    ds.ImageOrientationPatient = ["1", "0", "0", "0", "1", "0"]
    ds.PixelSpacing = ["1", "1"]
    ds.SliceThickness = "1"
    ds.Rows, ds.Columns = 2, 2
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 16, 15, 1
    ds.RescaleIntercept, ds.RescaleSlope = "-1024", "1"
    ds.PixelData = np.array([[0, 100], [200, 300]], dtype=np.int16).tobytes()
    return ds


def save(ds, path):
    ds.save_as(path, write_like_original=False)


# ----- round trip ----------------------------------------------------------------------------------------

NORMAL = (math.sin(math.radians(20)) * math.cos(math.radians(30)),
          math.sin(math.radians(20)) * math.sin(math.radians(30)), math.cos(math.radians(20)))
OUTER = dict(center=(12.5, -30.25, 41.0), axes=(30.0, 22.0, 40.0))
INNER = dict(center=(14.0, -28.0, 44.0), axes=(12.0, 10.0, 18.0))


def roundtrip(outdir, points, spacing):
    outer = ellipsoid_stack(OUTER["center"], OUTER["axes"], NORMAL, spacing, points)
    inner = ellipsoid_stack(INNER["center"], INNER["axes"], NORMAL, spacing, points)
    images = [uid(f"ct-image-{k}") for k in range(len(outer))]
    marker = [np.array(INNER["center"])]
    rois = [
        dict(number=1, name="Outer Ellipsoid", contours=outer, type="EXTERNAL"),
        dict(number=2, name="Inner Ellipsoid", contours=inner, type="ORGAN"),
        dict(number=3, name="Not Drawn", contours=[], type="ORGAN"),
        dict(number=4, name="Marker", contours=[(marker, "POINT")], type="MARKER"),
    ]
    save(rtstruct("roundtrip", rois, images), f"{outdir}/rtstruct.dcm")
    truth = {
        "space": "LPS",
        "normal": list(NORMAL),
        "volume_mm3": {
            "outer-ellipsoid": 4.0 / 3.0 * math.pi * np.prod(OUTER["axes"]),
            "inner-ellipsoid": 4.0 / 3.0 * math.pi * np.prod(INNER["axes"]),
        },
        "contours": [{"label": "outer-ellipsoid", "points": c.tolist()} for c in outer] +
                    [{"label": "inner-ellipsoid", "points": c.tolist()} for c in inner],
    }
    with open(f"{outdir}/truth.json", "w") as f:
        json.dump(truth, f)
    print(json.dumps({"outer_contours": len(outer), "inner_contours": len(inner)}))


def check(contours_json, truth_json):
    with open(contours_json) as f:
        read = json.load(f)
    with open(truth_json) as f:
        truth = json.load(f)
    got = [(c.get("label", ""), np.array(c["points"])) for fr in read["frames"] for c in fr["contours"]]
    worst, unmatched = 0.0, 0
    used = set()
    for t in truth["contours"]:
        tp = np.array(t["points"])
        best, best_k = math.inf, None
        for k, (label, pts) in enumerate(got):
            if k in used or label != t["label"] or pts.shape != tp.shape:
                continue
            d = float(np.max(np.linalg.norm(pts - tp, axis=1)))
            if d < best:
                best, best_k = d, k
        if best_k is None:
            unmatched += 1
            continue
        used.add(best_k)
        worst = max(worst, best)
    extra = len(got) - len(used)
    print(json.dumps({"max_error_mm": worst, "contours": len(used), "unmatched": unmatched, "extra": extra}))
    return 0 if unmatched == 0 and extra == 0 and worst <= 1e-3 else 1


# ----- the corpus ----------------------------------------------------------------------------------------


def small_stack(center=(0.0, 0.0, 0.0), axes=(10.0, 8.0, 6.0), normal=(0.0, 0.0, 1.0), spacing=3.0, points=10):
    return ellipsoid_stack(center, axes, normal, spacing, points)


def corpus(outdir):
    one = [dict(number=1, name="GTV", contours=small_stack())]
    two = [
        dict(number=7, name="Lung L", contours=small_stack((0, 0, 0), normal=NORMAL)),
        dict(number=9, name="Lung R", contours=small_stack((25, 0, 0), normal=NORMAL)),
    ]
    files = {}
    files["good_one_roi_axial.dcm"] = rtstruct("one", one, [uid("img-a"), uid("img-b")])
    files["good_two_rois_oblique.dcm"] = rtstruct("two", two)
    files["good_empty_roi_beside_a_drawn_one.dcm"] = rtstruct(
        "emptybeside", one + [dict(number=2, name="Empty", contours=[])])
    implicit = rtstruct("implicit", one)
    implicit.file_meta.TransferSyntaxUID = ImplicitVRLittleEndian
    files["good_implicit_vr.dcm"] = implicit

    files["bad_27_no_referenced_frame_of_reference.dcm"] = rtstruct("nofor", one, with_references=False)
    files["bad_27_roi_frame_of_reference_not_referenced.dcm"] = rtstruct(
        "otherfor", [dict(one[0], for_uid=uid("another-frame-of-reference"))])
    nouid = rtstruct("nouid", one)
    del nouid.StructureSetROISequence[0].ReferencedFrameOfReferenceUID
    files["bad_27_roi_without_frame_of_reference_uid.dcm"] = nouid

    files["bad_28_empty_roi.dcm"] = rtstruct("empty", [dict(number=1, name="GTV", contours=[])])
    files["bad_28_empty_contour_sequence.dcm"] = rtstruct(
        "emptyseq", [dict(number=1, name="GTV", contours=[], empty_sequence=True)])
    files["bad_28_only_point_contours.dcm"] = rtstruct(
        "points", [dict(number=1, name="Iso", contours=[([np.zeros(3)], "POINT")])])
    no_rois = rtstruct("norois", one)
    no_rois.StructureSetROISequence = Sequence()
    no_rois.ROIContourSequence = Sequence()
    no_rois.RTROIObservationsSequence = Sequence()
    files["bad_28_no_rois.dcm"] = no_rois

    files["bad_13_ct_image.dcm"] = ct_image("ct")
    wrong = rtstruct("wrongmod", one)
    wrong.Modality = "CT"
    files["bad_13_rtstruct_class_with_modality_ct.dcm"] = wrong
    plan = rtstruct("plan", one)
    plan.SOPClassUID = "1.2.840.10008.5.1.4.1.1.481.5"  # RT Plan Storage
    plan.file_meta.MediaStorageSOPClassUID = plan.SOPClassUID
    plan.Modality = "RTPLAN"
    files["bad_13_rt_plan.dcm"] = plan
    triplets = rtstruct("triplets", one)
    item = triplets.ROIContourSequence[0].ContourSequence[0]
    item.ContourData = list(item.ContourData)[:-1]
    files["bad_13_contour_data_not_triplets.dcm"] = triplets
    count = rtstruct("count", one)
    count.ROIContourSequence[0].ContourSequence[1].NumberOfContourPoints = 99
    files["bad_13_number_of_points_mismatch.dcm"] = count
    dangling = rtstruct("dangling", one)
    dangling.ROIContourSequence[0].ReferencedROINumber = 5
    files["bad_13_contour_of_undefined_roi.dcm"] = dangling
    notype = rtstruct("notype", one)
    del notype.ROIContourSequence[0].ContourSequence[0].ContourGeometricType
    files["bad_13_no_geometric_type.dcm"] = notype

    warnings.filterwarnings("ignore", message="Invalid value for VR DS")  # the NaN is the point
    nan = rtstruct("nan", one)
    data = list(nan.ROIContourSequence[0].ContourSequence[0].ContourData)
    data[4] = "nan"
    nan.ROIContourSequence[0].ContourSequence[0].ContourData = data
    files["bad_14_nan_coordinate.dcm"] = nan

    strict_one = [dict(number=1, name="GTV", contours=small_stack(points=8))]
    files["good_strict_seed.dcm"] = rtstruct("strictseed", strict_one)

    for name, ds in files.items():
        save(ds, f"{outdir}/{name}")
    # Truncated copies of a good file: inside ContourData, and between two items of a sequence.
    with open(f"{outdir}/good_one_roi_axial.dcm", "rb") as f:
        whole = f.read()
    with open(f"{outdir}/bad_12_truncated_in_contour_data.dcm", "wb") as f:
        f.write(whole[:len(whole) * 3 // 4])
    cut = whole.rfind(b"\xfe\xff\x00\xe0")  # the last item tag (FFFE,E000)
    with open(f"{outdir}/bad_12_truncated_between_items.dcm", "wb") as f:
        f.write(whole[:cut])
    with open(f"{outdir}/bad_12_header_only.dcm", "wb") as f:
        f.write(whole[:200])
    with open(f"{outdir}/bad_12_not_dicom.dcm", "wb") as f:
        f.write(b"this is a text file, not DICOM\n" * 8)
    open(f"{outdir}/bad_11_empty.dcm", "wb").close()


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("roundtrip")
    r.add_argument("outdir")
    r.add_argument("--points", type=int, default=48)
    r.add_argument("--spacing", type=float, default=4.0)
    c = sub.add_parser("check")
    c.add_argument("contours")
    c.add_argument("truth")
    k = sub.add_parser("corpus")
    k.add_argument("outdir")
    a = p.parse_args()
    if a.cmd == "roundtrip":
        roundtrip(a.outdir, a.points, a.spacing)
        return 0
    if a.cmd == "check":
        return check(a.contours, a.truth)
    corpus(a.outdir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
