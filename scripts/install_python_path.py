"""Makes Debian's python3 find the pedesis package of a build directory: writes
pedesis.pth (one line, the directory) into the user's site-packages. Run by
`make python`; undo by deleting the file it names."""
import os
import site
import sys


def main():
    if len(sys.argv) != 2 or not os.path.isdir(os.path.join(sys.argv[1], "pedesis")):
        sys.exit("usage: install_python_path.py BUILD/python (a directory holding pedesis/)")
    target = site.getusersitepackages()
    os.makedirs(target, exist_ok=True)
    path = os.path.join(target, "pedesis.pth")
    tmp = path + ".part"
    with open(tmp, "w") as f:
        f.write(os.path.abspath(sys.argv[1]) + "\n")
    os.replace(tmp, path)
    print(f"python: wrote {path}; /usr/bin/python3 -c 'import pedesis' now finds "
          f"{os.path.abspath(sys.argv[1])}/pedesis")


if __name__ == "__main__":
    main()
