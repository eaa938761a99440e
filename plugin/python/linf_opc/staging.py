"""Where a command's files go: the output folder, the lock that keeps a second run out of it
while one writes there, and the hidden folder inside it that holds a run's files until the whole
command has succeeded."""
import errno
import fcntl
import glob
import os
import shutil
import tempfile

from .arguments import UsageError

PARTIAL_PREFIX = ".linf_opc-partial-"
LOCK_NAME = ".linf_opc.lock"


def out_dir(args):
    d = args.get("out")
    if not d:
        raise UsageError("missing -rd out=DIR")
    try:
        os.makedirs(d, exist_ok=True)
    except OSError as e:
        raise UsageError("cannot create the output folder %s: %s" % (d, e.strerror))
    if not os.path.isdir(d):
        raise UsageError("the output folder %s is not a folder" % d)
    return d


class FolderLock:
    """The output folder's lock: an exclusive flock on DIR/.linf_opc.lock, held for the run. A
    second run into the folder refuses at once (a UsageError naming the holder's process id). The
    kernel drops the lock when its process ends, however it ends (SIGKILL included): a stale lock
    file blocks nothing. The holder removes the file as it lets go; a run that opened the old file
    just then finds it gone after locking and starts again on a fresh one, so two runs never hold
    locks on two different files at once."""

    def __init__(self, folder):
        self.path = os.path.join(folder, LOCK_NAME)
        self.fd = None
        while self.fd is None:
            try:
                fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
            except OSError as e:
                raise UsageError("cannot write into the output folder %s: %s" % (folder, e.strerror))
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as e:
                holder = _read_small(fd)
                os.close(fd)
                if e.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                    raise UsageError("another run is writing into the output folder %s%s; wait for it to "
                                     "end or choose another out=" % (folder, " (process %s)" % holder if holder
                                                                     else ""))
                raise UsageError("cannot lock the output folder %s: %s" % (folder, e.strerror))
            try:
                same = os.path.samestat(os.fstat(fd), os.stat(self.path))
            except OSError:
                same = False
            if not same:  # its holder removed it between our open and our lock: take a new one
                os.close(fd)
                continue
            self.fd = fd
        try:
            os.ftruncate(self.fd, 0)
            os.write(self.fd, b"%d\n" % os.getpid())
        except OSError:
            pass  # the process id is only for the second run's message (a full disk is seen later)

    def release(self):
        if self.fd is None:
            return
        try:
            os.remove(self.path)  # while still held: see the class's doc
        except OSError:
            pass
        os.close(self.fd)
        self.fd = None


def _read_small(fd):
    try:
        return os.pread(fd, 32, 0).decode("ascii", "replace").strip()
    except OSError:
        return ""


def remove_stale(folder):
    """Staging folders of runs that never finished (killed: SIGKILL, a power cut). Called with the
    folder's lock held, so no live run owns one of them."""
    for d in glob.glob(os.path.join(glob.escape(folder), PARTIAL_PREFIX + "*")):
        shutil.rmtree(d, ignore_errors=True)


class Staging:
    """Output files are written into a hidden folder inside the output folder and moved into
    place only when the whole command has succeeded: a failed or interrupted run leaves no
    half-written file behind (and the files of an earlier run stay as they were). The folder's
    lock (FolderLock) is held from here to commit or abort; a killed run's staging folder is
    removed by the next run into the folder."""
    open_ones = []

    def __init__(self, out):
        self.final = os.path.abspath(out_dir({"out": out}))
        self.lock = FolderLock(self.final)
        try:
            remove_stale(self.final)
            self.dir = tempfile.mkdtemp(prefix=PARTIAL_PREFIX, dir=self.final)
        except OSError as e:
            self.lock.release()
            raise UsageError("cannot write into the output folder %s: %s" % (self.final, e.strerror))
        except BaseException:
            self.lock.release()
            raise
        Staging.open_ones.append(self)

    def file(self, name):
        return os.path.join(self.dir, name)

    def commit(self):
        for name in sorted(os.listdir(self.dir)):
            os.replace(os.path.join(self.dir, name), os.path.join(self.final, name))
        self.abort()

    def abort(self):
        shutil.rmtree(self.dir, ignore_errors=True)
        self.lock.release()
        if self in Staging.open_ones:
            Staging.open_ones.remove(self)

    @classmethod
    def finish_all(cls, ok):
        for st in list(cls.open_ones):
            st.commit() if ok else st.abort()
