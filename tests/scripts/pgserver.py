"""A real PostgreSQL 15 for the store's tests: initdb + pg_ctl (Debian's /usr/lib/postgresql/15/bin) in a
temporary folder, listening only on a Unix socket there, run as an unprivileged user (the server refuses
root; as root the folder is given to `nobody`), trust authentication, stopped and removed afterwards,
also when a test fails (stop() from tearDownClass and atexit).

    server = PgServer.start()      # or None where PostgreSQL 15 or psycopg is missing (tests skip)
    url = server.url("oitbench")   # postgresql://postgres@/oitbench?host=/tmp/...&port=5431
    server.stop()
"""
import atexit
import os
import pwd
import shutil
import subprocess
import tempfile
import urllib.parse

PG_BIN = "/usr/lib/postgresql/15/bin"
PORT = 5431  # only names the socket file; nothing listens on TCP


def available():
    if not os.access(os.path.join(PG_BIN, "pg_ctl"), os.X_OK):
        return "PostgreSQL 15 not installed (apt-get install postgresql)"
    try:
        import psycopg  # noqa: F401
    except ImportError:
        return "psycopg 3 not installed (apt-get install python3-psycopg)"
    return None


class PgServer:
    def __init__(self, folder, user):
        self.folder, self.user = folder, user
        self.data = os.path.join(folder, "data")
        self.running = False

    @classmethod
    def start(cls):
        if available():
            return None
        folder = tempfile.mkdtemp(prefix="oitbench-pg-")
        os.chmod(folder, 0o755)
        user = None
        if os.geteuid() == 0:
            user = "nobody"
            pw = pwd.getpwnam(user)
            os.chown(folder, pw.pw_uid, pw.pw_gid)
        server = cls(folder, user)
        atexit.register(server.stop)
        try:
            server._run("initdb", "-D", server.data, "-U", "postgres", "--auth=trust", "-E", "UTF8",
                        "--no-sync", "--locale=C")
            opts = f"-c listen_addresses='' -c unix_socket_directories='{folder}' -p {PORT} -c fsync=off " \
                   "-c max_connections=40 -c shared_buffers=32MB"
            server._run("pg_ctl", "-D", server.data, "-o", opts, "-l", os.path.join(folder, "log"), "-w",
                        "-t", "60", "start")
            server.running = True
        except Exception:
            server.stop()
            raise
        return server

    def _run(self, tool, *args):
        cmd = [os.path.join(PG_BIN, tool)] + list(args)
        if self.user:
            cmd = ["runuser", "-u", self.user, "--"] + cmd
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120, cwd=self.folder)
        if proc.returncode != 0:
            log = ""
            if os.path.exists(os.path.join(self.folder, "log")):
                with open(os.path.join(self.folder, "log"), encoding="utf-8", errors="replace") as f:
                    log = f.read()[-2000:]
            raise RuntimeError(f"{tool} failed ({proc.returncode}): {proc.stdout}{proc.stderr}{log}")
        return proc

    def url(self, database):
        """A URL for `database`, created (empty) if it does not exist yet."""
        import psycopg
        with psycopg.connect(self._url("postgres"), autocommit=True) as c:
            if not c.execute("SELECT 1 FROM pg_database WHERE datname = %s", (database,)).fetchone():
                c.execute(f'CREATE DATABASE "{database}"')
        return self._url(database)

    def drop(self, database):
        import psycopg
        with psycopg.connect(self._url("postgres"), autocommit=True) as c:
            c.execute(f'DROP DATABASE IF EXISTS "{database}" WITH (FORCE)')

    def _url(self, database):
        return f"postgresql://postgres@/{database}?host={urllib.parse.quote(self.folder, safe='/')}&port={PORT}"

    def stop(self):
        if self.running:
            try:
                self._run("pg_ctl", "-D", self.data, "-m", "immediate", "-w", "-t", "30", "stop")
            except Exception:  # noqa: BLE001: the folder goes anyway
                pass
            self.running = False
        shutil.rmtree(self.folder, ignore_errors=True)
