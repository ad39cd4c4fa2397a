"""Bad input raises the topoplex exceptions (ValueError, OSError kinds) with the library's
message; never a crash: wrong dtype, non-contiguous, negative or out-of-range ids, NaN."""

import threading

import numpy as np
import pytest

import topoplex


def test_the_hierarchy_is_value_os_and_memory_errors():
    assert issubclass(topoplex.InputError, ValueError)
    assert issubclass(topoplex.DomainError, topoplex.InputError)
    assert issubclass(topoplex.ReadError, OSError)
    assert issubclass(topoplex.WriteError, OSError)
    assert issubclass(topoplex.TopoplexMemoryError, MemoryError)
    for e in (topoplex.InputError, topoplex.ReadError, topoplex.TopoplexMemoryError):
        assert issubclass(e, topoplex.TopoplexError)


def test_bad_arrays_are_refused_with_a_message():
    with pytest.raises(topoplex.InputError, match="negative"):
        topoplex.Complex.from_arrays(np.array([[0, -1, 2]]))
    with pytest.raises(topoplex.InputError, match="integer"):
        topoplex.Complex.from_arrays(np.array([[0.0, 1.0]]))
    with pytest.raises(topoplex.InputError, match="32 bits"):
        topoplex.Complex.from_arrays(np.array([[0, 2**40]]))
    with pytest.raises(topoplex.InputError, match="repeats vertex"):
        topoplex.Complex.from_arrays(np.array([[0, 1, 1]]))
    with pytest.raises(topoplex.InputError, match="vertex 7"):
        topoplex.Complex.from_arrays(np.array([[0, 1, 7]]), n_vertices=3)
    with pytest.raises(topoplex.InputError, match="CSR"):
        topoplex.Complex.from_arrays((np.array([0, 5]), np.array([0, 1, 2])))
    with pytest.raises(topoplex.InputError, match="no vertex"):
        topoplex.Complex.from_arrays([np.array([[0, 1]]), np.zeros((2, 0), dtype=np.int64)])


def test_non_contiguous_and_other_dtypes_are_copied_once_and_give_the_same_complex():
    base = np.array([[0, 9, 1, 9, 2], [1, 9, 2, 9, 3]], dtype=np.int16)
    strided = base[:, ::2]
    assert not strided.flags.c_contiguous
    a = topoplex.Complex.from_arrays(strided)
    b = topoplex.Complex.from_arrays(np.array([[0, 1, 2], [1, 2, 3]], dtype=np.uint32))
    assert a.census() == b.census()


def test_nan_coordinates_do_not_crash():
    pts = np.full((3, 3), np.nan)
    try:
        c = topoplex.Complex.from_arrays(np.array([[0, 1, 2]]), points=pts)
    except topoplex.InputError as e:
        assert "coordinates" in str(e) or "finite" in str(e)
    else:
        assert np.isnan(c.points).all()
        with pytest.raises(topoplex.InputError):
            topoplex.simplify(c, 0.5)


def test_queries_out_of_range_raise():
    s = topoplex.Complex.from_arrays(np.array([[0, 1, 2]]), n_vertices=4).build("ig")
    with pytest.raises(topoplex.InputError, match="not in the complex"):
        s.locate([0, 3])
    with pytest.raises(topoplex.InputError):
        s.relation(3, 0)
    with pytest.raises(topoplex.InputError):
        s.relation(1, 2, simplices=[0, 99])
    with pytest.raises(topoplex.InputError, match="negative"):
        s.relation(1, 2, simplices=[-1])
    with pytest.raises(topoplex.InputError, match="uses vertex 9"):
        s.locate([0, 9])
    assert s.locate(np.array([[0, 1], [0, 3]])).tolist() == [0, -1]
    with pytest.raises(topoplex.InputError, match="unknown structure"):
        topoplex.Complex.from_arrays(np.array([[0, 1]])).build("nope")


def test_a_structure_outside_its_domain_names_the_simplex():
    c = topoplex.Complex.from_arrays(np.array([[0, 1, 2, 3]]))
    with pytest.raises(topoplex.DomainError, match="ts"):
        c.build("ts")
    with pytest.raises(ValueError):
        c.build("de")


def test_files_raise_os_errors_with_the_path_and_line(tmp_path):
    with pytest.raises(topoplex.ReadError):
        topoplex.read(tmp_path / "missing.off")
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    with pytest.raises(OSError, match="bad.off"):
        topoplex.read(bad)
    c = topoplex.Complex.from_arrays(np.array([[0, 1, 2, 3]]))
    with pytest.raises(topoplex.WriteError):
        c.write(tmp_path / "tet.off")
    with pytest.raises(topoplex.ReadError):
        topoplex.open(bad)


def test_edits_on_a_fixed_structure_are_refused():
    s = topoplex.Complex.from_arrays(np.array([[0, 1, 2]])).build("ia")
    with pytest.raises(topoplex.InputError, match="not editable"):
        s.insert([[0, 3]])


def test_two_threads_query_one_structure_and_get_the_same_answers():
    rng = np.random.default_rng(7)
    tets = np.sort(rng.choice(40, size=(300, 4), replace=True), axis=1)
    tets = tets[(np.diff(tets, axis=1) > 0).all(axis=1)]
    s = topoplex.Complex.from_arrays(tets).build("sig")
    want = s.relation(0, 3)
    got = [None, None]

    def work(i):
        for _ in range(5):
            got[i] = s.relation(0, 3)

    ts = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    for g in got:
        assert g[0].tolist() == want[0].tolist() and g[1].tolist() == want[1].tolist()


def test_arrays_out_own_their_memory_and_outlive_their_structure():
    s = topoplex.Complex.from_arrays(np.array([[0, 1, 2], [1, 2, 3]])).build("ig")
    rows = s.simplices(1)
    off, ids = s.relation(1, 2)
    del s
    assert rows.tolist() == [[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]]
    assert rows.base is not None and rows.flags.c_contiguous and rows.dtype == np.uint32
    assert ids.tolist() == [0, 0, 0, 1, 1, 1]


def test_a_forked_child_queries_and_exits():
    import os
    import sys

    if not hasattr(os, "fork"):
        pytest.skip("no fork")
    s = topoplex.Complex.from_arrays(np.array([[0, 1, 2, 3], [1, 2, 3, 4]])).build("sig")
    want = s.relation(0, 3)[1].tolist()
    s.relation(1, 2)  # the parent has used the library (and its pool) before the fork
    pid = os.fork()
    if pid == 0:
        code = 0 if s.relation(0, 3)[1].tolist() == want else 3
        os._exit(code)
    import time

    deadline = time.monotonic() + 60
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        if time.monotonic() > deadline:
            os.kill(pid, 9)
            pytest.fail("the forked child hung")
        time.sleep(0.05)
    assert os.waitstatus_to_exitcode(status) == 0
    sys.stdout.flush()


def test_the_extension_checks_its_arrays_itself():
    # The private entry points the package calls, given what the package would refuse: an
    # InputError, never a panic or a crash.
    from topoplex import _core

    ids = np.array([0, 1, 2], dtype=np.uint32)
    for offsets in ([1, 3], [0, 2, 1, 3], [0, 5]):
        with pytest.raises(topoplex.InputError, match="CSR"):
            _core.Complex._from_csr(3, ids, np.array(offsets, dtype=np.uintp), None)
    live = topoplex.Complex.from_arrays(np.array([[0, 1, 2], [1, 2, 3]])).live()
    with pytest.raises(topoplex.InputError, match="positions"):
        live._s._contract(np.array([[1, 2]], dtype=np.uint32), "free", np.zeros((2, 3)))
