"""pas.study.inputs.read_lf_peaks: the LF peak loader of ``pas run`` and ``pas study``."""

import numpy as np
import pandas as pd
import pytest

from pas.study.inputs import read_lf_peaks

RUN = {"file": "LF_FILE", "column": "--lf-column", "id_column": "--id-column",
       "meta_columns": "--meta-columns"}


@pytest.fixture
def csv(tmp_path):
    path = tmp_path / "peaks.csv"
    pd.DataFrame({"id": ["a", "b", "c"], "rwe": [1.0, 2.5, 0.5], "seed": [1, 2, 3]}).to_csv(
        path, index=False)
    return path


@pytest.mark.parametrize("parquet", [False, True])
def test_table_with_ids_and_meta(csv, parquet):
    if parquet:
        pd.read_csv(csv).to_parquet(csv.with_suffix(".parquet"))
        csv = csv.with_suffix(".parquet")
    lf, ids, meta = read_lf_peaks(csv, column="rwe", id_column="id", meta_columns=["seed"])
    np.testing.assert_array_equal(lf, [1.0, 2.5, 0.5])
    assert ids == ["a", "b", "c"] and meta == [{"seed": 1}, {"seed": 2}, {"seed": 3}]


def test_guessed_columns(tmp_path, csv):
    path = tmp_path / "one.csv"
    pd.DataFrame({"height": [1.0, 2.0]}).to_csv(path, index=False)
    lf, ids, meta = read_lf_peaks(path, guess_columns=True)
    assert lf.tolist() == [1.0, 2.0] and ids is None and meta is None
    _, ids, _ = read_lf_peaks(csv, column="rwe", guess_columns=True)
    assert ids == ["a", "b", "c"]  # "id" is taken when present
    with pytest.raises(ValueError, match="--lf-column: peaks.csv has columns"):
        read_lf_peaks(csv, guess_columns=True, names=RUN)
    with pytest.raises(ValueError, match=r"^column is missing \(the column of peaks.csv"):
        read_lf_peaks(csv)


def test_npy(tmp_path):
    plain = tmp_path / "plain.npy"
    np.save(plain, np.array([1.0, 2.0, 3.0]))
    lf, ids, meta = read_lf_peaks(plain)
    assert lf.tolist() == [1.0, 2.0, 3.0] and ids is None and meta is None
    with pytest.raises(ValueError, match="lf.id_column needs a structured array"):
        read_lf_peaks(plain, id_column="id", names={"id_column": "lf.id_column"})
    np.save(tmp_path / "square.npy", np.ones((2, 2)))
    with pytest.raises(ValueError, match="LF_FILE square.npy: expected a 1-D array"):
        read_lf_peaks(tmp_path / "square.npy", names=RUN)
    rec = tmp_path / "rec.npy"
    np.save(rec, np.array([(7, 1.5), (9, 0.5)], dtype=[("id", "i8"), ("lf", "f8")]))
    lf, ids, _ = read_lf_peaks(rec, guess_columns=True)
    assert lf.tolist() == [1.5, 0.5] and ids == [7, 9] and isinstance(ids[0], int)


@pytest.mark.parametrize("kw, text, needle", [
    ({"column": "nope"}, None, "--lf-column: column 'nope' is missing from peaks.csv"),
    ({"column": "rwe", "id_column": "x"}, None, "--id-column: column 'x' is missing"),
    ({"column": "rwe", "meta_columns": ["t"]}, None, "--meta-columns: column 't' is missing"),
    ({"column": "rwe"}, "rwe\n1\nabc\n", "--lf-column: column 'rwe' of peaks.csv has a missing"
                                        " or non-numeric value in data row 2"),
    ({"column": "rwe", "id_column": "id"}, "id,rwe\na,1\n,2\n", "--id-column: column 'id' of "
                                                               "peaks.csv is empty in data row 2"),
    ({"column": "rwe", "id_column": "id"}, "id,rwe\na,1\na,2\n", "repeats the id 'a'"),
])
def test_errors_name_the_field(csv, kw, text, needle):
    if text is not None:
        csv.write_text(text)
    with pytest.raises(ValueError) as exc:
        read_lf_peaks(csv, names=RUN, **kw)
    assert needle in str(exc.value) and "\n" not in str(exc.value)


def test_file_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="lf.file .*none.csv does not exist"):
        read_lf_peaks(tmp_path / "none.csv", column="lf", names={"file": "lf.file"})
    (tmp_path / "peaks.xlsx").write_text("x")
    with pytest.raises(ValueError, match="LF_FILE peaks.xlsx: unsupported format '.xlsx'"):
        read_lf_peaks(tmp_path / "peaks.xlsx", names=RUN)
