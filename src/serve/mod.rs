//! `awl serve`: the CPU as a virtual PLC on the network, paced to the wall clock. The protocol
//! servers (S7comm, Modbus TCP) sit here at the edge; they reach the CPU only through the
//! requests of [`request`], served at the cycle control point.

pub mod modbus;
pub mod request;
