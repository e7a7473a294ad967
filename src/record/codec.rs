//! The byte form of a sealed step.
//!
//! A log is one `Vec<u8>` of steps, each `[len][body][len reversed]`, so it
//! can be walked from either end (undo pops from the top, trimming drops
//! from the bottom). All integers are LEB128 varints; signed differences
//! are zigzagged. The body:
//!
//! | part | when | content |
//! |---|---|---|
//! | flags | always | bit 0 `more` (the step's unit goes on below it in pop order), bits 1–7 which parts follow |
//! | half-edges | some changed | count; per record, ascending: `(slot − previous) << 3 \| mask`, then each changed field (origin, next, face) as the zigzagged difference from the same field of the previous record |
//! | vertex links | some changed | count; per vertex: slot delta, zigzagged difference from the previous half-edge |
//! | face links | some changed | count; per face: slot delta, `zigzag(half-edge − previous) << 1 \| hole` |
//! | slots | births, deaths or reuses | a mask of arenas with births, with deaths/reuses and with new slots vacant at the seal; per arena with births `count, start`, and where some are vacant the number of runs and every run length but the last (alternating live, vacant, ...); per arena with events `count`, then per event `zigzag(slot − previous) << 1 \| kind` and, for a death, the generation the element had (events only for slots older than the step) |
//! | holes | the count changed | zigzagged difference (after − before) |
//! | states | an arena's fast-path state changed | 5 bits per arena: changed, before, after |
//! | side | column records, column structure or a whole mesh | how many side records (kept beside the bytes) belong to the step |
//!
//! The values stored are the ones to put back: old ones in the undo log,
//! new ones in the redo log. Applying a step swaps them with the mesh's and
//! re-encodes what it took out, so undo writes the redo step and redo the
//! undo step. The slot events are the forward history in both logs; the
//! direction of application decides what they do.

use super::{Arena, PerArena};
use crate::layout::{FaceLink, Fid, HalfedgeRecord, Hid, Vid};
use crate::slots::State;

/// Which parts a body holds.
const MORE: u64 = 1;
const HE: u64 = 1 << 1;
const VH: u64 = 1 << 2;
const FL: u64 = 1 << 3;
const SLOTS: u64 = 1 << 4;
const HOLES: u64 = 1 << 5;
const STATES: u64 = 1 << 6;
const SIDE: u64 = 1 << 7;

/// Field bits of a half-edge entry's mask.
pub(crate) const ORIGIN: u8 = 1;
pub(crate) const NEXT: u8 = 2;
pub(crate) const FACE: u8 = 4;

/// A birth or death in one arena, in the order they happened.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum SlotEvent {
    /// The element at `generation` in `slot` was removed.
    Death { slot: u32, generation: u32 },
    /// A vacant slot from the free list was taken, for an element of
    /// `generation`.
    Reuse { slot: u32, generation: u32 },
}

/// One step, decoded (or about to be encoded).
#[derive(Default, Debug)]
pub(crate) struct Step {
    /// The step's unit goes on below it in pop order.
    pub(crate) more: bool,
    /// `(slot, changed fields, the values to put back in those fields)`.
    pub(crate) he: Vec<(Hid, u8, HalfedgeRecord)>,
    pub(crate) vh: Vec<(Vid, Hid)>,
    pub(crate) fl: Vec<(Fid, FaceLink)>,
    /// Per arena (vertex, edge, face): new slots at the end, `(start, count)`.
    pub(crate) births: PerArena<(u32, u32)>,
    /// Per arena: which of the new slots were live when the step was
    /// sealed, as run lengths over `births` alternating live, vacant,
    /// live, ... (the first run may be empty). Empty: all live. A new slot
    /// that died (or died and was reused) in the step has no event: this
    /// and the slot's generation say all that undo and redo need.
    pub(crate) born_live: PerArena<Vec<u32>>,
    /// Per arena: deaths and reuses of slots older than the step, in order.
    pub(crate) events: PerArena<Vec<SlotEvent>>,
    /// Hole count after minus before.
    pub(crate) holes: i64,
    /// Per arena: the fast-path state before and after, where it changed.
    pub(crate) states: PerArena<Option<(State, State)>>,
    /// Side records of the step.
    pub(crate) side: u32,
}

impl Step {
    /// Empty it for reuse, keeping capacity.
    pub(crate) fn clear(&mut self) {
        self.more = false;
        self.he.clear();
        self.vh.clear();
        self.fl.clear();
        self.births = PerArena::default();
        for r in self.born_live.iter_mut() {
            r.clear();
        }
        for e in self.events.iter_mut() {
            e.clear();
        }
        self.holes = 0;
        self.states = PerArena::default();
        self.side = 0;
    }

    /// Whether it holds nothing at all.
    pub(crate) fn is_empty(&self) -> bool {
        self.he.is_empty()
            && self.vh.is_empty()
            && self.fl.is_empty()
            && self.births.iter().all(|b| b.1 == 0)
            && self.events.iter().all(Vec::is_empty)
            && self.holes == 0
            && self.states.iter().all(Option::is_none)
            && self.side == 0
    }
}

#[inline]
pub(crate) fn put(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push(v as u8 | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

#[inline]
fn zigzag(v: i64) -> u64 {
    ((v << 1) ^ (v >> 63)) as u64
}

#[inline]
fn unzigzag(v: u64) -> i64 {
    (v >> 1) as i64 ^ -((v & 1) as i64)
}

/// `a − b` of two 32-bit ids, zigzagged.
#[inline]
fn diff(a: u32, b: u32) -> u64 {
    zigzag(i64::from(a) - i64::from(b))
}

/// `b + d` back.
#[inline]
fn undiff(b: u32, d: u64) -> u32 {
    (i64::from(b) + unzigzag(d)) as u32
}

fn state_bits(s: State) -> u64 {
    match s {
        State::Intact => 0,
        State::Pristine => 1,
        State::Mixed => 2,
    }
}

fn bits_state(b: u64) -> State {
    match b & 3 {
        0 => State::Intact,
        1 => State::Pristine,
        _ => State::Mixed,
    }
}

/// Append `step` as one framed step. The body is written in place after
/// room for its length, sized from [`size_hint`]; only when the body's
/// length needs another number of bytes than guessed does it move (no
/// scratch copy of the body, and for a large step usually no move).
pub(crate) fn encode(step: &Step, out: &mut Vec<u8>) {
    encode_with(step, out, None);
}

/// Half-edge records written straight into a body, for the caller to
/// produce in the middle of [`encode_with`]: at most `.0` records, by
/// `.1`, each through [`HeWriter::push`].
pub(crate) type DirectHe<'a> = (usize, &'a mut dyn FnMut(&mut Vec<u8>, &mut HeWriter));

/// [`encode`], with the half-edge records (if `direct`) written by the
/// caller into the log itself instead of coming from `step.he` (which is
/// then empty): a large step's records never sit in a vector of their
/// own. The record count goes before them as a varint padded to the width
/// of the bound (the decoder reads it as any varint).
pub(crate) fn encode_with(step: &Step, out: &mut Vec<u8>, direct: Option<DirectHe<'_>>) {
    let extra = direct.as_ref().map_or(0, |d| d.0);
    let frame = out.len();
    let hint = size_hint(step) + extra * 5;
    let guess = varint_len(hint as u64);
    // Room for the largest body this step can take, at once: a large step
    // then never regrows (copies and re-faults) the log by doubling. Slack
    // a large step leaves is given back below (the log's capacity is what
    // the history's memory counts).
    let bound = max_size(step) + extra * 24 + 10;
    let grew = out.capacity() - out.len() < bound;
    out.reserve(bound);
    out.resize(frame + guess, 0);
    encode_body(step, out, direct);
    let len = out.len() - frame - guess;
    let k = varint_len(len as u64);
    if k != guess {
        if k > guess {
            out.resize(out.len() + k - guess, 0);
        }
        out.copy_within(frame + guess..frame + guess + len, frame + k);
        out.truncate(frame + k + len);
    }
    let mut prefix = Vec::with_capacity(k);
    put(&mut prefix, len as u64);
    out[frame..frame + k].copy_from_slice(&prefix);
    // The length again, reversed, so the step can be found from its end.
    let mark = out.len();
    put(out, len as u64);
    out[mark..].reverse();
    if grew && bound > 1 << 16 {
        out.shrink_to(out.len() + out.len() / 8);
    }
}

/// The most bytes `step`'s body can take (every varint at its longest).
fn max_size(step: &Step) -> usize {
    64 + step.he.len() * 24
        + (step.vh.len() + step.fl.len()) * 16
        + step.events.iter().map(|e| e.len() * 16).sum::<usize>()
        + step.born_live.iter().map(|r| r.len() * 5).sum::<usize>()
}

/// About how many bytes `step`'s body takes (to reserve once).
fn size_hint(step: &Step) -> usize {
    16 + step.he.len() * 5
        + (step.vh.len() + step.fl.len()) * 4
        + step.events.iter().map(|e| e.len() * 3).sum::<usize>()
}

/// Writes half-edge records in the body's form (slot and field deltas
/// from the previous record), one at a time, ascending by slot.
#[derive(Default)]
pub(crate) struct HeWriter {
    slot: u32,
    origin: u32,
    next: u32,
    face: u32,
    count: usize,
}

impl HeWriter {
    /// Append the record of half-edge `h`: the fields in `mask`, with the
    /// values `r` holds for them.
    #[inline]
    pub(crate) fn push(&mut self, body: &mut Vec<u8>, h: Hid, mask: u8, r: HalfedgeRecord) {
        put(body, u64::from(h.raw() - self.slot) << 3 | u64::from(mask));
        self.slot = h.raw();
        if mask & ORIGIN != 0 {
            put(body, diff(r.origin.raw(), self.origin));
            self.origin = r.origin.raw();
        }
        if mask & NEXT != 0 {
            put(body, diff(r.next.raw(), self.next));
            self.next = r.next.raw();
        }
        if mask & FACE != 0 {
            put(body, diff(r.face.raw(), self.face));
            self.face = r.face.raw();
        }
        self.count += 1;
    }
}

/// `step`'s body, appended to `body` (half-edge records by `direct`, if
/// given: see [`encode_with`]).
fn encode_body(step: &Step, body: &mut Vec<u8>, direct: Option<DirectHe<'_>>) {
    let has_slots =
        step.births.iter().any(|b| b.1 > 0) || step.events.iter().any(|e| !e.is_empty());
    let mut flags = u64::from(step.more);
    for (on, bit) in [
        (!step.he.is_empty() || direct.is_some(), HE),
        (!step.vh.is_empty(), VH),
        (!step.fl.is_empty(), FL),
        (has_slots, SLOTS),
        (step.holes != 0, HOLES),
        (step.states.iter().any(Option::is_some), STATES),
        (step.side > 0, SIDE),
    ] {
        if on {
            flags |= bit;
        }
    }
    put(body, flags);
    if let Some(direct) = direct {
        encode_direct_halfedges(body, direct);
    } else if !step.he.is_empty() {
        put(body, step.he.len() as u64);
        let mut w = HeWriter::default();
        for &(h, mask, r) in &step.he {
            w.push(body, h, mask, r);
        }
    }
    encode_links(step, body);
    if has_slots {
        encode_slots(step, body);
    }
    if step.holes != 0 {
        put(body, zigzag(step.holes));
    }
    if step.states.iter().any(Option::is_some) {
        let mut bits = 0u64;
        for a in Arena::ALL {
            if let Some((before, after)) = step.states[a] {
                let b = 1 | state_bits(before) << 1 | state_bits(after) << 3;
                bits |= b << (5 * a.index());
            }
        }
        put(body, bits);
    }
    if step.side > 0 {
        put(body, u64::from(step.side));
    }
}

/// The half-edge records the caller writes (see [`encode_with`]), after
/// their count, padded to the width of the bound.
fn encode_direct_halfedges(body: &mut Vec<u8>, (max, write): DirectHe<'_>) {
    let width = varint_len(max as u64);
    let at = body.len();
    body.resize(at + width, 0);
    let mut w = HeWriter::default();
    write(body, &mut w);
    debug_assert!(w.count <= max, "more half-edge records than the bound");
    let mut c = w.count as u64;
    for b in &mut body[at..at + width - 1] {
        *b = (c & 0x7f) as u8 | 0x80;
        c >>= 7;
    }
    body[at + width - 1] = c as u8;
}

/// The vertex and face links of `step`.
fn encode_links(step: &Step, body: &mut Vec<u8>) {
    if !step.vh.is_empty() {
        put(body, step.vh.len() as u64);
        let (mut slot, mut prev) = (0u32, 0u32);
        for &(v, h) in &step.vh {
            put(body, u64::from(v.raw() - slot));
            put(body, diff(h.raw(), prev));
            slot = v.raw();
            prev = h.raw();
        }
    }
    if !step.fl.is_empty() {
        put(body, step.fl.len() as u64);
        let (mut slot, mut prev) = (0u32, 0u32);
        for &(f, l) in &step.fl {
            put(body, u64::from(f.raw() - slot));
            let h = l.halfedge().raw();
            put(body, diff(h, prev) << 1 | u64::from(l.is_hole()));
            slot = f.raw();
            prev = h;
        }
    }
}

/// The slots part: births (and which new slots are vacant), then the
/// deaths and reuses of older slots, per arena.
fn encode_slots(step: &Step, body: &mut Vec<u8>) {
    let mut mask = 0u64;
    for a in Arena::ALL {
        let i = a.index();
        if step.births[a].1 > 0 {
            mask |= 1 << i;
        }
        if !step.events[a].is_empty() {
            mask |= 8 << i;
        }
        if step.births[a].1 > 0 && !step.born_live[a].is_empty() {
            mask |= 64 << i;
        }
    }
    put(body, mask);
    for (&(start, count), runs) in step.births.iter().zip(step.born_live.iter()) {
        if count > 0 {
            put(body, u64::from(count));
            put(body, u64::from(start));
            if !runs.is_empty() {
                // The last run is what the others leave of `count`.
                put(body, runs.len() as u64);
                for &r in &runs[..runs.len() - 1] {
                    put(body, u64::from(r));
                }
            }
        }
    }
    for events in step.events.iter() {
        if events.is_empty() {
            continue;
        }
        put(body, events.len() as u64);
        let mut prev = 0u32;
        for e in events {
            let (slot, generation, kind) = match *e {
                SlotEvent::Death { slot, generation } => (slot, generation, 0),
                SlotEvent::Reuse { slot, generation } => (slot, generation, 1),
            };
            put(body, diff(slot, prev) << 1 | kind);
            put(body, u64::from(generation));
            prev = slot;
        }
    }
}

/// Reads varints forward.
struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    #[inline]
    fn get(&mut self) -> u64 {
        let mut v = 0u64;
        let mut shift = 0;
        loop {
            let b = self.bytes[self.pos];
            self.pos += 1;
            v |= u64::from(b & 0x7f) << shift;
            if b < 0x80 {
                return v;
            }
            shift += 7;
        }
    }

    #[inline]
    fn get32(&mut self) -> u32 {
        self.get() as u32
    }
}

/// The body of the step that ends at `end`: `(start of the framed step,
/// body range)`.
pub(crate) fn last_step(bytes: &[u8], end: usize) -> (usize, std::ops::Range<usize>) {
    // The reversed length: read backwards.
    let mut len = 0u64;
    let mut shift = 0;
    let mut pos = end;
    loop {
        pos -= 1;
        let b = bytes[pos];
        len |= u64::from(b & 0x7f) << shift;
        if b < 0x80 {
            break;
        }
        shift += 7;
    }
    let body_end = pos;
    let body_start = body_end - len as usize;
    let prefix = varint_len(len);
    (body_start - prefix, body_start..body_end)
}

/// The step that starts at `start`: `(end of the framed step, body range)`.
pub(crate) fn first_step(bytes: &[u8], start: usize) -> (usize, std::ops::Range<usize>) {
    let mut r = Reader { bytes, pos: start };
    let len = r.get() as usize;
    let body = r.pos..r.pos + len;
    (body.end + varint_len(len as u64), body)
}

fn varint_len(mut v: u64) -> usize {
    let mut n = 1;
    while v >= 0x80 {
        v >>= 7;
        n += 1;
    }
    n
}

/// Decode a body into `step` (cleared first).
pub(crate) fn decode(body: &[u8], step: &mut Step) {
    step.clear();
    let mut r = Reader {
        bytes: body,
        pos: 0,
    };
    let flags = r.get();
    step.more = flags & MORE != 0;
    if flags & HE != 0 {
        decode_halfedges(&mut r, step);
    }
    if flags & VH != 0 {
        let n = r.get() as usize;
        let (mut slot, mut prev) = (0u32, 0u32);
        for _ in 0..n {
            slot += r.get32();
            prev = undiff(prev, r.get());
            step.vh.push((Vid::new(slot), Hid::new(prev)));
        }
    }
    if flags & FL != 0 {
        let n = r.get() as usize;
        let (mut slot, mut prev) = (0u32, 0u32);
        for _ in 0..n {
            slot += r.get32();
            let k = r.get();
            prev = undiff(prev, k >> 1);
            step.fl
                .push((Fid::new(slot), FaceLink::new(Hid::new(prev), k & 1 == 1)));
        }
    }
    if flags & SLOTS != 0 {
        decode_slots(&mut r, step);
    }
    if flags & HOLES != 0 {
        step.holes = unzigzag(r.get());
    }
    if flags & STATES != 0 {
        let bits = r.get();
        for a in Arena::ALL {
            let b = bits >> (5 * a.index());
            if b & 1 == 1 {
                step.states[a] = Some((bits_state(b >> 1), bits_state(b >> 3)));
            }
        }
    }
    if flags & SIDE != 0 {
        step.side = r.get32();
    }
    debug_assert_eq!(r.pos, body.len(), "a step decoded to a different length");
}

/// The half-edge records (see [`HeWriter`]).
fn decode_halfedges(r: &mut Reader<'_>, step: &mut Step) {
    let n = r.get() as usize;
    step.he.reserve(n);
    let (mut slot, mut o, mut nx, mut f) = (0u32, 0u32, 0u32, 0u32);
    for _ in 0..n {
        let k = r.get();
        slot += (k >> 3) as u32;
        let mask = (k & 7) as u8;
        let mut rec = HalfedgeRecord::VACANT;
        if mask & ORIGIN != 0 {
            o = undiff(o, r.get());
            rec.origin = Vid::new(o);
        }
        if mask & NEXT != 0 {
            nx = undiff(nx, r.get());
            rec.next = Hid::new(nx);
        }
        if mask & FACE != 0 {
            f = undiff(f, r.get());
            rec.face = Fid::new(f);
        }
        step.he.push((Hid::new(slot), mask, rec));
    }
}

/// The slots part (see [`encode_slots`]).
fn decode_slots(r: &mut Reader<'_>, step: &mut Step) {
    let mask = r.get();
    for a in Arena::ALL {
        if mask & (1 << a.index()) != 0 {
            let count = r.get32();
            let start = r.get32();
            step.births[a] = (start, count);
            if mask & (64 << a.index()) != 0 {
                let n = r.get() as usize;
                let runs = &mut step.born_live[a];
                let mut left = count;
                for _ in 1..n {
                    let k = r.get32();
                    runs.push(k);
                    left -= k;
                }
                runs.push(left);
            }
        }
    }
    for a in Arena::ALL {
        if mask & (8 << a.index()) == 0 {
            continue;
        }
        let n = r.get() as usize;
        let mut prev = 0u32;
        for _ in 0..n {
            let k = r.get();
            let slot = undiff(prev, k >> 1);
            prev = slot;
            let generation = r.get32();
            step.events[a].push(if k & 1 == 1 {
                SlotEvent::Reuse { slot, generation }
            } else {
                SlotEvent::Death { slot, generation }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Step {
        let mut s = Step {
            more: true,
            ..Step::default()
        };
        s.he.push((
            Hid::new(4),
            ORIGIN | FACE,
            HalfedgeRecord {
                origin: Vid::new(3),
                next: Hid::NONE,
                face: Fid::new(9),
            },
        ));
        s.he.push((
            Hid::new(1000),
            NEXT,
            HalfedgeRecord {
                origin: Vid::NONE,
                next: Hid::new(2),
                face: Fid::NONE,
            },
        ));
        s.vh.push((Vid::new(7), Hid::NONE));
        s.vh.push((Vid::new(8), Hid::new(0)));
        s.fl.push((Fid::new(2), FaceLink::new(Hid::new(5), true)));
        s.births = PerArena([(10, 2), (0, 0), (100_000, 7)]);
        s.born_live[Arena::Face] = vec![0, 3, 2, 2];
        s.events[Arena::Edge].push(SlotEvent::Death {
            slot: 5,
            generation: 3,
        });
        s.events[Arena::Edge].push(SlotEvent::Reuse {
            slot: 5,
            generation: 7,
        });
        s.events[Arena::Edge].push(SlotEvent::Death {
            slot: 1,
            generation: u32::MAX - 2,
        });
        s.holes = -2;
        s.states[Arena::Face] = Some((State::Intact, State::Mixed));
        s.side = 3;
        s
    }

    fn masked(s: &Step) -> Vec<(Hid, u8, [u32; 3])> {
        s.he.iter()
            .map(|&(h, m, r)| {
                let pick = |bit: u8, v: u32| if m & bit != 0 { v } else { 0 };
                (
                    h,
                    m,
                    [
                        pick(ORIGIN, r.origin.raw()),
                        pick(NEXT, r.next.raw()),
                        pick(FACE, r.face.raw()),
                    ],
                )
            })
            .collect()
    }

    #[test]
    fn steps_round_trip_from_both_ends() {
        let s = sample();
        let mut log = Vec::new();
        encode(&Step::default(), &mut log);
        let first_end = log.len();
        encode(&s, &mut log);
        // From the end.
        let (start, range) = last_step(&log, log.len());
        assert_eq!(start, first_end);
        let mut d = Step::default();
        decode(&log[range.clone()], &mut d);
        assert_eq!(masked(&d), masked(&s));
        assert_eq!((d.vh.clone(), d.fl.clone()), (s.vh.clone(), s.fl.clone()));
        assert_eq!((d.births, d.events.clone()), (s.births, s.events.clone()));
        assert_eq!(d.born_live, s.born_live);
        assert_eq!((d.more, d.holes, d.states, d.side), (true, -2, s.states, 3));
        // From the start.
        let (end, r0) = first_step(&log, 0);
        assert_eq!(end, first_end);
        let (end, r1) = first_step(&log, end);
        assert_eq!((end, r1), (log.len(), range));
        decode(&log[r0], &mut d);
        assert!(d.is_empty() && !d.more);
    }

    /// Bodies whose length takes fewer, and more, bytes than the size
    /// hint guessed: the body moves, and both ends still find it.
    #[test]
    fn bodies_off_the_guessed_length_frame_correctly() {
        let mut short = Step::default();
        for i in 0..30u32 {
            short.vh.push((Vid::new(i), Hid::new(i)));
        }
        let mut long = Step::default();
        for i in 0..10u32 {
            // Every field jumps across the id range from one record to the
            // next: five bytes each.
            let far = if i % 2 == 0 { u32::MAX - 7 } else { 0 };
            long.he.push((
                Hid::new(i * 100_000),
                ORIGIN | NEXT | FACE,
                HalfedgeRecord {
                    origin: Vid::new(far),
                    next: Hid::new(i),
                    face: Fid::new(far),
                },
            ));
        }
        assert!(varint_len(size_hint(&short) as u64) > 1);
        assert_eq!(varint_len(size_hint(&long) as u64), 1);
        let mut log = vec![0x55];
        encode(&short, &mut log);
        let mid = log.len();
        encode(&long, &mut log);
        let mut d = Step::default();
        let (start, range) = last_step(&log, log.len());
        assert_eq!(start, mid);
        assert!(range.len() >= 128, "the long body needs two length bytes");
        decode(&log[range], &mut d);
        assert_eq!(masked(&d), masked(&long));
        let (start, range) = last_step(&log, mid);
        assert_eq!(start, 1);
        assert!(range.len() < 128);
        decode(&log[range], &mut d);
        assert_eq!(d.vh, short.vh);
        let (end, _) = first_step(&log, 1);
        assert_eq!(end, mid);
    }

    /// Records written straight into the log (padded count) decode as the
    /// same step as records from `step.he`, for bounds of any width.
    #[test]
    fn direct_half_edge_records_decode_as_the_same_step() {
        for max in [2usize, 200, 100_000] {
            let s = sample();
            let mut log = vec![0x11];
            let mut bare = sample();
            let records = std::mem::take(&mut bare.he);
            encode_with(
                &bare,
                &mut log,
                Some((max, &mut |body: &mut Vec<u8>, w: &mut HeWriter| {
                    for &(h, mask, r) in &records {
                        w.push(body, h, mask, r);
                    }
                })),
            );
            let (start, range) = last_step(&log, log.len());
            assert_eq!(start, 1);
            let mut d = Step::default();
            decode(&log[range], &mut d);
            assert_eq!(masked(&d), masked(&s));
            assert_eq!(
                (d.vh.clone(), d.births, d.side),
                (s.vh.clone(), s.births, 3)
            );
            let (end, _) = first_step(&log, 1);
            assert_eq!(end, log.len());
        }
    }

    #[test]
    fn long_bodies_frame_correctly() {
        let mut s = Step::default();
        for i in 0..5000u32 {
            s.vh.push((
                Vid::new(i * 7),
                Hid::new((u64::from(i) * 1_000_003 % 4_000_000) as u32),
            ));
        }
        let mut log = vec![0xAA];
        encode(&s, &mut log);
        let (start, range) = last_step(&log, log.len());
        assert_eq!(start, 1);
        let mut d = Step::default();
        decode(&log[range], &mut d);
        assert_eq!(d.vh, s.vh);
    }
}
