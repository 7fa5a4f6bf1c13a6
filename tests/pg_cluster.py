"""A throw-away PostgreSQL server for the archive tests, and the fixtures that use it.

The session starts one cluster in a temporary folder with Debian's (or PATH's) ``initdb`` and
``pg_ctl``, listening on 127.0.0.1 on a free port and on a unix socket in that folder, trust
authentication on loopback only; it is stopped and removed at the end. PostgreSQL refuses to
run as root: run as root (CI in a container), the server runs as ``nobody``. Without the
binaries the PostgreSQL half of the tests skips, saying so (``.ci/run`` installs Debian's
``postgresql`` package when it runs as root, so CI always has them).

Each test gets its own database (``pg_db``), made with ``pdcp-studio archive init``'s own
code, and two logins: ``anna`` (a fitter, full name "Anna Berg" in the operator table) and
``rita`` (a reader). ``archive_url`` runs a test once on SQLite and once on PostgreSQL.
"""

from __future__ import annotations

import glob
import itertools
import os
import shutil
import socket
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pytest

ADMIN = "postgres"
FITTER, FITTER_NAME = "anna", "Anna Berg"
READER = "rita"
#: A fitter who must give a password (``PASSWORD``): the sign-in tests.
PASSWORD_ROLE, PASSWORD = "pia", "correct horse"
_numbers = itertools.count(1)


def pg_bindir() -> Path | None:
    """The folder with ``initdb`` and ``pg_ctl``: PATH, else Debian's newest version."""
    found = shutil.which("initdb")
    if found and shutil.which("pg_ctl"):
        return Path(found).parent
    for candidate in sorted(glob.glob("/usr/lib/postgresql/*/bin"), reverse=True,
                            key=lambda p: int(p.split("/")[-2]) if p.split("/")[-2].isdigit() else 0):
        if Path(candidate, "initdb").exists() and Path(candidate, "pg_ctl").exists():
            return Path(candidate)
    return None


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class Cluster:
    """One running server; ``stop()``/``start()`` for the fault tests."""

    def __init__(self, bindir: Path, *, durable: bool = False) -> None:
        self.bindir = bindir
        self.durable = durable  # fsync on (a benchmark's figures), off for the tests
        self.base = Path(tempfile.mkdtemp(prefix="pdcp-pg-"))
        self.data = self.base / "data"
        self.port = _free_port()
        self._as = []
        if os.geteuid() == 0:  # postgres refuses root: the server runs as nobody
            self._as = ["runuser", "-u", "nobody", "--"]
            os.chown(self.base, 65534, 65534)
        os.chmod(self.base, 0o755)
        self._run("initdb", "-D", str(self.data), "-U", ADMIN, "--auth=trust",
                  "--encoding=UTF8", "--no-sync")
        # Loopback only; one login signs in with a password (the app's sign-in dialog).
        hba = self.data / "pg_hba.conf"
        hba.write_text("local all all trust\n"
                       f"host all {PASSWORD_ROLE} 127.0.0.1/32 scram-sha-256\n"
                       "host all all 127.0.0.1/32 trust\n")
        self.start()

    def _run(self, tool: str, *args: str) -> None:
        result = subprocess.run([*self._as, str(self.bindir / tool), *args],
                                capture_output=True, text=True, timeout=120)
        if result.returncode != 0:
            raise RuntimeError(f"{tool} failed: {result.stdout}\n{result.stderr}")

    def start(self) -> None:
        options = (f"-c listen_addresses=127.0.0.1 -p {self.port} "
                   f"-c unix_socket_directories={self.base}"
                   + ("" if self.durable else " -c fsync=off"))
        self._run("pg_ctl", "-D", str(self.data), "-l", str(self.base / "log"), "-o", options,
                  "-w", "-t", "60", "start")

    def stop(self, mode: str = "fast") -> None:
        self._run("pg_ctl", "-D", str(self.data), "-m", mode, "-w", "stop")

    def url(self, role: str, db: str = "postgres") -> str:
        return f"postgresql://{role}@127.0.0.1:{self.port}/{db}"

    def sql(self, statement: str, db: str = "postgres", role: str = ADMIN) -> None:
        import psycopg

        with psycopg.connect(self.url(role, db), autocommit=True) as conn:
            conn.execute(statement)

    def remove(self) -> None:
        try:
            self.stop("immediate")
        except RuntimeError:
            pass
        shutil.rmtree(self.base, ignore_errors=True)


@dataclass
class Database:
    cluster: Cluster
    name: str

    @property
    def admin(self) -> str:
        return self.cluster.url(ADMIN, self.name)

    @property
    def fitter(self) -> str:
        return self.cluster.url(FITTER, self.name)

    @property
    def reader(self) -> str:
        return self.cluster.url(READER, self.name)


@pytest.fixture(scope="session")
def pg_cluster():
    bindir = pg_bindir()
    if bindir is None:
        pytest.skip("no PostgreSQL server binaries (initdb, pg_ctl) on PATH or in "
                    "/usr/lib/postgresql/*/bin: install Debian's postgresql package")
    try:
        import psycopg  # noqa: F401
    except ImportError:
        pytest.skip("psycopg is not installed (pip install -e '.[test]' brings it)")
    cluster = Cluster(bindir)
    try:
        for role, group in ((FITTER, "pdcp_fitter"), (READER, "pdcp_reader")):
            cluster.sql(f"DO $$ BEGIN IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = "
                        f"'{group}') THEN CREATE ROLE {group} NOLOGIN; END IF; END $$")
            cluster.sql(f"CREATE ROLE {role} LOGIN IN ROLE {group}")
        cluster.sql(f"CREATE ROLE {PASSWORD_ROLE} LOGIN PASSWORD '{PASSWORD}' IN ROLE pdcp_fitter")
        yield cluster
    finally:
        cluster.remove()


@pytest.fixture
def pg_db(pg_cluster):
    """A fresh database with the archive's schema (``archive init``) and the operator table
    naming the fitter."""
    from pdcp_studio.storage.archive.postgres import init_schema

    if not _running(pg_cluster):
        pg_cluster.start()
    name = f"t{os.getpid()}_{next(_numbers)}"
    pg_cluster.sql(f"CREATE DATABASE {name}")
    db = Database(pg_cluster, name)
    init_schema(db.admin)
    pg_cluster.sql(f"INSERT INTO pdcp.operators VALUES ('{FITTER}', '{FITTER_NAME}')", name)
    yield db
    if not _running(pg_cluster):
        pg_cluster.start()
    pg_cluster.sql(f"DROP DATABASE {name} WITH (FORCE)")


def _running(cluster: Cluster) -> bool:
    with socket.socket() as s:
        return s.connect_ex(("127.0.0.1", cluster.port)) == 0


@pytest.fixture(params=["sqlite", "postgresql"])
def archive_url(request, tmp_path, monkeypatch):
    """The URL of an empty archive, once per engine; the journal in the test's own folder."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path / 'history.sqlite'}"
    return request.getfixturevalue("pg_db").fitter
