"""A study's output folder: manifest, chunk files, results.
"""
from __future__ import annotations

import json
import os
import uuid
from pathlib import Path

import pandas as pd

from fastrock.studies.definition import FORMAT, StudyError


#: Rows per chunk.  bench/bench_study.py on the 2-core machine: 20-32 ms of
#: overhead per chunk (packing, kernel launch, Parquet file, Dask round trip)
#: against 9-12 ms of wall time per row (records of 30-40 s), so chunks of
#: 34-64 rows or more keep it under 5 %; 128 (about 2 %) leaves a margin for
#: shorter records and busier machines.
DEFAULT_CHUNK_SIZE = 128

MANIFEST = "manifest.json"

RESULTS_DIR = "results"


# ============================================================ output folder
def need_pyarrow():
    """Raise a StudyError naming the install command when pyarrow is missing."""
    try:
        import pyarrow  # noqa: F401
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise StudyError("study results are Parquet files and need pyarrow: "
                         "pip install 'fastrock[distributed]' (or pip install pyarrow)") from None


def _chunk_path(folder, cid):
    return Path(folder) / RESULTS_DIR / f"chunk-{cid}.parquet"


def atomic_write_bytes(path, data):
    """Write ``data`` to ``path`` through a temporary file and os.replace (a reader never sees
    half a file)."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, path)


def arrow_table(cols, study_hash):
    """A pyarrow Table of the chunk columns (object arrays -> string), with
    the study hash in the schema metadata.  Built from the arrays directly:
    going through pandas costs more than the rest of a small chunk."""
    import pyarrow as pa
    arrays = {k: pa.array(v, type=pa.string()) if v.dtype == object else pa.array(v)
              for k, v in cols.items()}
    return pa.table(arrays, metadata={b"fastrock_study": study_hash.encode()})


def write_chunk(folder, cid, cols, study_hash):
    """Write the chunk's file atomically (temporary name, then os.replace)."""
    import pyarrow.parquet as pq
    path = _chunk_path(folder, cid)
    if isinstance(cols, pd.DataFrame):
        cols = {k: cols[k].to_numpy(dtype=object if cols[k].dtype.kind not in "biuf" else None)
                for k in cols.columns}
    table = arrow_table(cols, study_hash)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    pq.write_table(table, tmp)
    os.replace(tmp, path)


def chunk_done(folder, chunk, study_hash):
    """The chunk's file exists, is readable and belongs to this study."""
    import pyarrow.parquet as pq
    path = _chunk_path(folder, chunk.id)
    if not path.is_file():
        return False
    try:
        md = pq.read_metadata(path)
    except Exception:  # noqa: BLE001 - unreadable: rerun the chunk
        return False
    meta = md.metadata or {}
    return md.num_rows == chunk.rows.size and meta.get(b"fastrock_study") == study_hash.encode()


def manifest_of(plan, study):
    """The manifest.json contents of a study's plan."""
    prep = plan.prep
    return {
        "format": FORMAT,
        "study_hash": prep.hash,
        "name": study.name,
        "chunk_size": plan.chunk_size,
        "n_rows": int(plan.n),
        "records": [r.name for r in prep.records],
        "bodies": prep.body_labels,
        "variants": prep.variant_names,
        "measure": prep.measure,
        "levels": prep.levels.tolist(),
        "solver": prep.solver.name,
        "t_after": prep.t_after,
        "chunks": [{"id": c.id, "kernel": c.kernel, "n_rows": int(c.rows.size),
                    "first_row": int(c.rows[0]), "file": f"{RESULTS_DIR}/chunk-{c.id}.parquet"}
                   for c in plan.chunks],
    }


def _read_manifest(folder):
    path = Path(folder) / MANIFEST
    if not path.is_file():
        return None
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise StudyError(f"{path}: unreadable manifest ({exc}); remove the folder or choose "
                         f"another output") from None


def check_folder(folder, prep, chunk_size):
    """Chunk size to use; StudyError if the folder holds another study."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise StudyError(f"output {folder} exists and is not a folder")
    man = _read_manifest(folder)
    if man is None:
        if (folder / RESULTS_DIR).is_dir() and any((folder / RESULTS_DIR).iterdir()):
            raise StudyError(f"output folder {folder} holds results but no {MANIFEST}: "
                             f"choose an empty folder")
        return int(chunk_size or DEFAULT_CHUNK_SIZE)
    if man.get("study_hash") != prep.hash:
        raise StudyError(
            f"output folder {folder} holds a different study (hash {str(man.get('study_hash'))[:12]}"
            f", this study {prep.hash[:12]}): choose a new output folder, or delete that one")
    if chunk_size is not None and int(chunk_size) != int(man["chunk_size"]):
        raise StudyError(f"output folder {folder} was started with chunk_size="
                         f"{man['chunk_size']}; resume with the same chunk size (or omit it)")
    return int(man["chunk_size"])


def load_results(folder):
    """All finished rows of a study folder as one DataFrame.

    Columns as in :data:`RESULT_COLUMNS`, sorted by ``row``.
    ``df.attrs``: ``study_hash``, ``complete`` (every chunk present),
    ``missing_chunks`` (ids).
    """
    need_pyarrow()
    import pyarrow.parquet as pq
    folder = Path(folder)
    man = _read_manifest(folder)
    if man is None:
        raise StudyError(f"{folder}: no {MANIFEST}; not a study folder")
    frames, missing = [], []
    for c in man["chunks"]:
        path = folder / c["file"]
        if not path.is_file():
            missing.append(c["id"])
            continue
        t = pq.read_table(path)
        if (t.schema.metadata or {}).get(b"fastrock_study") != man["study_hash"].encode():
            raise StudyError(f"{path} belongs to another study")
        frames.append(t.replace_schema_metadata(None))
    if frames:
        import pyarrow as pa
        df = pa.concat_tables(frames).to_pandas()
        df = df.sort_values("row", kind="stable").reset_index(drop=True)
    else:
        df = pd.DataFrame()
    df.attrs.update(study_hash=man["study_hash"], complete=not missing, missing_chunks=missing,
                    n_rows=man["n_rows"])
    return df


