#!/usr/bin/env python3
"""Checks a PNG written by fe (stdlib only: zlib and struct, 8-bit RGB or RGBA, non-interlaced).

check_png.py FILE [--size WxH] [--channels 3|4] [--pixel X,Y=R,G,B[,A] ...] [--not-black]
             [--like OTHER.png FRACTION]
--like: at most FRACTION of the pixels differ from OTHER's (same size) by more than 5 in a channel.
Exit 0 when every check holds, 1 with the first that does not (a pixel within 1 of each value).
"""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        sys.exit(f'{path}: not a PNG')
    i, idat = 8, b''
    while i < len(data):
        n = struct.unpack('>I', data[i:i + 4])[0]
        kind = data[i + 4:i + 8]
        if kind == b'IHDR':
            w, h, depth, colour = struct.unpack('>IIBB', data[i + 8:i + 18])
        elif kind == b'IDAT':
            idat += data[i + 8:i + 8 + n]
        i += 12 + n
    if depth != 8 or colour not in (2, 6):
        sys.exit(f'{path}: not 8-bit RGB or RGBA (depth {depth}, colour type {colour})')
    ch = 3 if colour == 2 else 4
    raw, stride, rows, prev = zlib.decompress(idat), w * ch, [], bytearray(w * ch)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):  # the five PNG filters
            a = line[x - ch] if x >= ch else 0
            b = prev[x]
            c = prev[x - ch] if x >= ch else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, ch, rows


def main(argv):
    path, args = argv[1], argv[2:]
    w, h, ch, rows = read_png(path)
    while args:
        opt = args.pop(0)
        if opt == '--size':
            want = args.pop(0)
            if f'{w}x{h}' != want: sys.exit(f'{path}: size {w}x{h}, expected {want}')
        elif opt == '--channels':
            want = int(args.pop(0))
            if ch != want: sys.exit(f'{path}: {ch} channels, expected {want}')
        elif opt == '--pixel':
            where, values = args.pop(0).split('=')
            x, y = (int(v) for v in where.split(','))
            want = [int(v) for v in values.split(',')]
            got = list(rows[y][x * ch:x * ch + ch])
            if any(abs(g - v) > 1 for g, v in zip(got, want)) or len(want) > ch:
                sys.exit(f'{path}: pixel {x},{y} is {got}, expected {want}')
        elif opt == '--not-black':
            if max(max(r[i] for i in range(len(r)) if ch == 3 or i % 4 != 3) for r in rows) <= 1:
                sys.exit(f'{path}: every pixel is black')
        elif opt == '--like':
            other, fraction = args.pop(0), float(args.pop(0))
            ow, oh, och, orows = read_png(other)
            if (ow, oh, och) != (w, h, ch): sys.exit(f'{path}: {w}x{h}x{ch}, {other} is {ow}x{oh}x{och}')
            differ = sum(any(abs(rows[y][x * ch + c] - orows[y][x * ch + c]) > 5 for c in range(ch))
                         for y in range(h) for x in range(w))
            if differ > fraction * w * h: sys.exit(f'{path}: {differ} of {w * h} pixels differ from {other} by more than 5')
        else:
            sys.exit(f'unknown option {opt}')
    print(f'{path}: {w}x{h}, {ch} channels: checks hold')


if __name__ == '__main__':
    main(sys.argv)
