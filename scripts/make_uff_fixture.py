"""Universal-file fixtures written by pyuff, the peer an engineer would otherwise use.

Writes, into tests/fixtures/uff/:
- pyuff_mixed.uff: datasets 151, 164, 15, 2411, 58 (complex double FRF, real double coherence,
  real single time response, complex double FRF on an uneven abscissa, real double PSD of
  function type 9, complex single FRF), 55 (real normal mode 3 DOF, real normal mode 6 DOF,
  complex mode), all ASCII;
- pyuff_58b.uff: three binary 58b datasets (complex double even, real double uneven, complex
  double uneven), little endian, as pyuff writes them (abscissa in double precision);
- pyuff_mixed.json, pyuff_58b.json: the inputs given to pyuff, in file order. Every real is a
  string (Python repr) so that Rust's correctly rounded `str::parse` recovers the exact double;
  each real array says with how many significant digits pyuff writes it ("digits"), so that
  the test compares the values read with the inputs rounded to those digits. The binary file
  stores doubles, exactly ("digits": 17).

pyuff's formats: 58 double values %20.11e (12 significant digits), abscissa minimum and
increment %13.5e (6), uneven abscissa %13.5e (6), single precision %13.5e (6); 55 %13.5e (6);
15 %13.5E (6); 2411 %25.16e (17, exact); 164 %25.16e (17, exact).

Run with the project's Python peer:  $(bash scripts/python-env.sh) scripts/make_uff_fixture.py
"""

import json
import os

import numpy as np
import pyuff

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "fixtures", "uff")


def reals(values, digits):
    return {"values": [repr(float(v)) for v in values], "digits": digits}


def complexes(values, digits):
    values = np.asarray(values)
    return {
        "re": [repr(float(v)) for v in values.real],
        "im": [repr(float(v)) for v in values.imag],
        "digits": digits,
    }


def frf_set(**kw):
    """A dataset 58 dict with the fields every function here shares."""
    base = dict(
        type=58,
        binary=0,
        id1="NONE",
        id2="NONE",
        id3="NONE",
        id4="NONE",
        id5="NONE",
        rsp_ent_name="NONE",
        ref_ent_name="NONE",
        abscissa_spec_data_type=18,
        abscissa_axis_lab="Frequency",
        abscissa_axis_units_lab="Hz",
        ordinate_spec_data_type=12,
        ordinate_axis_lab="Acceleration",
        ordinate_axis_units_lab="m/s^2",
        orddenom_spec_data_type=13,
        orddenom_axis_lab="Force",
        orddenom_axis_units_lab="N",
        z_axis_spec_data_type=0,
    )
    base.update(kw)
    return base


def expected_58(d, digits_y, digits_x):
    e = {
        "type": 58,
        "id1": d["id1"],
        "id2": d["id2"],
        "func_type": int(d["func_type"]),
        "rsp_node": int(d["rsp_node"]),
        "rsp_dir": int(d["rsp_dir"]),
        "ref_node": int(d["ref_node"]),
        "ref_dir": int(d["ref_dir"]),
        "rsp_ent_name": d["rsp_ent_name"],
        "abscissa_spacing": int(d["abscissa_spacing"]),
        "double": d.get("ord_data_type", 4) in (4, 6),
        "x": reals(d["x"], digits_x),
        "abscissa_axis": [d["abscissa_spec_data_type"], d["abscissa_axis_lab"], d["abscissa_axis_units_lab"]],
        "ordinate_axis": [d["ordinate_spec_data_type"], d["ordinate_axis_lab"], d["ordinate_axis_units_lab"]],
        "denominator_axis": [d["orddenom_spec_data_type"], d["orddenom_axis_lab"], d["orddenom_axis_units_lab"]],
    }
    if np.iscomplexobj(d["data"]):
        e["data"] = complexes(d["data"], digits_y)
    else:
        e["data"] = reals(d["data"], digits_y)
    return e


def write(path, sets, force_double):
    if os.path.exists(path):
        os.remove(path)
    uff = pyuff.UFF(path)
    for dset, double in zip(sets, force_double):
        uff.write_sets([dset], mode="add", force_double=double)


def mixed(rng):
    sets, doubles, expected = [], [], []

    header = dict(type=151, model_name="jointid fixture", description="written by pyuff",
                  db_app="make_uff_fixture.py", date_db_created="01-Jan-25", time_db_created="12:00:00",
                  version_db1="1", version_db2="2", file_type="0", date_db_saved="01-Jan-25",
                  time_db_saved="12:00:01", program="pyuff " + pyuff.__version__,
                  date_file_written="01-Jan-25", time_file_written="12:00:02")
    sets.append(header); doubles.append(True)
    expected.append({"type": 151, "model_file": "jointid fixture", "description": "written by pyuff",
                     "program": "pyuff " + pyuff.__version__})

    units = dict(type=164, units_code=5, units_description="mm (milli newton)", temp_mode=2,
                 length=1000.0, force=1000.0, temp=1.0, temp_offset=273.15)
    sets.append(units); doubles.append(True)
    expected.append({"type": 164, "units_code": 5, "description": "mm (milli newton)", "temp_mode": 2,
                     "factors": reals([1000.0, 1000.0, 1.0, 273.15], 17)})

    labels = [1, 2, 3, 100]
    xyz = rng.normal(size=(4, 3))
    nodes15 = dict(type=15, node_nums=labels, def_cs=[0, 1, 2, 0], disp_cs=[0, 0, 3, 1], color=[1, 8, 11, 1],
                   x=xyz[:, 0], y=xyz[:, 1], z=xyz[:, 2])
    sets.append(nodes15); doubles.append(True)
    expected.append({"type": 15, "labels": labels, "def_cs": [0, 1, 2, 0], "disp_cs": [0, 0, 3, 1],
                     "color": [1, 8, 11, 1], "xyz": reals(xyz.ravel(), 6)})

    xyz2 = rng.normal(size=(3, 3)) * 1e-3
    nodes2411 = dict(type=2411, node_nums=[7, 8, 9], def_cs=[1, 1, 1], disp_cs=[1, 1, 2], color=[5, 5, 5],
                     x=xyz2[:, 0], y=xyz2[:, 1], z=xyz2[:, 2])
    sets.append(nodes2411); doubles.append(True)
    expected.append({"type": 2411, "labels": [7, 8, 9], "def_cs": [1, 1, 1], "disp_cs": [1, 1, 2],
                     "color": [5, 5, 5], "xyz": reals(xyz2.ravel(), 17)})

    n = 64
    f = np.arange(n) * 0.5
    h = rng.normal(size=n) + 1j * rng.normal(size=n)
    d = frf_set(func_type=4, id1="H1 point 1", id2="jointid fixture", rsp_node=1, rsp_dir=3, ref_node=10,
                ref_dir=-3, rsp_ent_name="ACC1", abscissa_spacing=1, data=h, x=f)
    sets.append(d); doubles.append(True); expected.append(expected_58(d, 12, 6))

    c = rng.uniform(size=n)
    d = frf_set(func_type=6, id1="coherence point 1", rsp_node=1, rsp_dir=3, ref_node=10, ref_dir=-3,
                abscissa_spacing=1, data=c, x=f, ordinate_spec_data_type=0, ordinate_axis_lab="NONE",
                ordinate_axis_units_lab="NONE", orddenom_spec_data_type=0, orddenom_axis_lab="NONE",
                orddenom_axis_units_lab="NONE")
    sets.append(d); doubles.append(True); expected.append(expected_58(d, 12, 6))

    t = -0.01 + np.arange(50) * 1e-3
    y = rng.normal(size=50)
    d = frf_set(func_type=1, id1="time response", rsp_node=2, rsp_dir=2, ref_node=0, ref_dir=0,
                abscissa_spacing=1, ord_data_type=2, data=y, x=t, abscissa_spec_data_type=17,
                abscissa_axis_lab="Time", abscissa_axis_units_lab="s", orddenom_spec_data_type=0,
                orddenom_axis_lab="NONE", orddenom_axis_units_lab="NONE")
    sets.append(d); doubles.append(False); expected.append(expected_58(d, 6, 6))

    fu = np.sort(rng.uniform(1.0, 200.0, size=21))
    hu = rng.normal(size=21) + 1j * rng.normal(size=21)
    d = frf_set(func_type=4, id1="H1 point 3, uneven", rsp_node=3, rsp_dir=1, ref_node=10, ref_dir=-3,
                abscissa_spacing=0, data=hu, x=fu)
    sets.append(d); doubles.append(True); expected.append(expected_58(d, 12, 6))

    psd = rng.uniform(size=n) * 1e-6
    d = frf_set(func_type=9, id1="PSD point 4", rsp_node=4, rsp_dir=3, ref_node=4, ref_dir=3,
                abscissa_spacing=1, data=psd, x=f)
    sets.append(d); doubles.append(True); expected.append(expected_58(d, 12, 6))

    hs = rng.normal(size=15) + 1j * rng.normal(size=15)
    d = frf_set(func_type=4, id1="H1 point 2, single precision", rsp_node=2, rsp_dir=3, ref_node=10,
                ref_dir=-3, abscissa_spacing=1, ord_data_type=5, data=hs, x=f[:15])
    sets.append(d); doubles.append(False); expected.append(expected_58(d, 6, 6))

    shape_nodes = [1, 2, 3, 100]
    r = rng.normal(size=(3, 4))
    d = dict(type=55, id1="mode 1", id2="NONE", id3="NONE", id4="NONE", id5="NONE", model_type=1,
             analysis_type=2, data_ch=2, spec_data_type=8, load_case=1, mode_n=1, freq=18.7532,
             modal_m=1.5, modal_damp_vis=0.012, modal_damp_his=0.0, node_nums=shape_nodes,
             r1=r[0], r2=r[1], r3=r[2])
    sets.append(d); doubles.append(True)
    expected.append({"type": 55, "analysis_type": 2, "data_ch": 2, "spec_data_type": 8, "mode_n": 1,
                     "load_case": 1, "ndv": 3, "nodes": shape_nodes,
                     "params": reals([18.7532, 1.5, 0.012, 0.0], 6), "values": reals(r.T.ravel(), 6)})

    r6 = rng.normal(size=(6, 2))
    d = dict(type=55, id1="mode 2, 6 DOF", id2="NONE", id3="NONE", id4="NONE", id5="NONE", model_type=1,
             analysis_type=2, data_ch=3, spec_data_type=8, load_case=1, mode_n=2, freq=98.4,
             modal_m=0.75, modal_damp_vis=0.004, modal_damp_his=0.0, node_nums=[1, 2],
             r1=r6[0], r2=r6[1], r3=r6[2], r4=r6[3], r5=r6[4], r6=r6[5])
    sets.append(d); doubles.append(True)
    expected.append({"type": 55, "analysis_type": 2, "data_ch": 3, "spec_data_type": 8, "mode_n": 2,
                     "load_case": 1, "ndv": 6, "nodes": [1, 2],
                     "params": reals([98.4, 0.75, 0.004, 0.0], 6), "values": reals(r6.T.ravel(), 6)})

    rc = rng.normal(size=(3, 3)) + 1j * rng.normal(size=(3, 3))
    eig = -3.2 + 1j * 620.5
    d = dict(type=55, id1="complex mode 3", id2="NONE", id3="NONE", id4="NONE", id5="NONE", model_type=1,
             analysis_type=3, data_ch=2, spec_data_type=8, load_case=1, mode_n=3, eig=eig,
             modal_a=0.25 - 0.5j, modal_b=1.5 + 2.0j, node_nums=[1, 2, 3], r1=rc[0], r2=rc[1], r3=rc[2])
    sets.append(d); doubles.append(True)
    expected.append({"type": 55, "analysis_type": 3, "data_ch": 2, "spec_data_type": 8, "mode_n": 3,
                     "load_case": 1, "ndv": 3, "nodes": [1, 2, 3],
                     "params": reals([eig.real, eig.imag, 0.25, -0.5, 1.5, 2.0], 6),
                     "values": complexes(rc.T.ravel(), 6)})
    return sets, doubles, expected


def binary(rng):
    sets, expected = [], []
    n = 40
    f = np.arange(n) * 0.25
    h = rng.normal(size=n) + 1j * rng.normal(size=n)
    d = frf_set(binary=1, func_type=4, id1="binary FRF", rsp_node=5, rsp_dir=2, ref_node=10, ref_dir=2,
                abscissa_spacing=1, data=h, x=f)
    sets.append(d); expected.append(expected_58(d, 17, 6))
    fu = np.sort(rng.uniform(0.0, 50.0, size=17))
    c = rng.uniform(size=17)
    d = frf_set(binary=1, func_type=6, id1="binary coherence, uneven", rsp_node=5, rsp_dir=2, ref_node=10,
                ref_dir=2, abscissa_spacing=0, data=c, x=fu)
    sets.append(d); expected.append(expected_58(d, 17, 17))
    hu = rng.normal(size=17) + 1j * rng.normal(size=17)
    d = frf_set(binary=1, func_type=4, id1="binary FRF, uneven", rsp_node=6, rsp_dir=-1, ref_node=10,
                ref_dir=2, abscissa_spacing=0, data=hu, x=fu)
    sets.append(d); expected.append(expected_58(d, 17, 17))
    return sets, expected


def main():
    os.makedirs(OUT, exist_ok=True)
    rng = np.random.default_rng(20250101)
    sets, doubles, expected = mixed(rng)
    write(os.path.join(OUT, "pyuff_mixed.uff"), sets, doubles)
    with open(os.path.join(OUT, "pyuff_mixed.json"), "w") as fh:
        json.dump({"pyuff": pyuff.__version__, "records": expected}, fh, indent=1)
    sets, expected = binary(rng)
    write(os.path.join(OUT, "pyuff_58b.uff"), sets, [True] * len(sets))
    with open(os.path.join(OUT, "pyuff_58b.json"), "w") as fh:
        json.dump({"pyuff": pyuff.__version__, "records": expected}, fh, indent=1)
    # pyuff reads its own files back: the fixture is what pyuff means.
    for name in ("pyuff_mixed.uff", "pyuff_58b.uff"):
        back = pyuff.UFF(os.path.join(OUT, name)).read_sets()
        print(name, [s["type"] for s in back])


if __name__ == "__main__":
    main()
