//! `awl serve`: the CPU as a virtual PLC on the network, paced to the wall clock. The protocol
//! servers (S7comm, Modbus TCP, the online page's HTTP, OPC UA) sit here at the edge; they reach the
//! CPU only through the requests of [`request`], served at the cycle control point by
//! [`station`] (the online page's by [`online`], an attached debugger's by [`hold`]).

pub mod access;
pub mod hold;
pub mod http;
pub mod identity;
mod listen;
pub mod modbus;
pub mod network;
pub mod notation;
pub mod online;
pub mod opcua;
pub mod pacing;
pub mod plc;
pub mod request;
pub mod s7comm;
pub mod station;
#[cfg(test)]
pub(crate) mod testing;
